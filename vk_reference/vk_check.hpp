// VkResult → exception: device loss and out-of-memory become DeviceError (model/errors.hpp),
// every other failure a std::runtime_error naming the call.
#pragma once

#include <vulkan/vulkan.h>

namespace rastercmp::vk {

// The enumerator's name, e.g. "VK_ERROR_DEVICE_LOST".
const char* result_name(VkResult result);

// Throws unless `result` is VK_SUCCESS. `call` names the Vulkan function for the message.
void check(VkResult result, const char* call);

}  // namespace rastercmp::vk
