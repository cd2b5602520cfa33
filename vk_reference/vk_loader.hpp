// The Vulkan loader, opened at run time (dlopen) rather than linked: the rastercmp executable
// has no NEEDED libvulkan, so the CPU backend runs where no loader is installed and a Vulkan
// command without one ends with EnvironmentError (exit 3) and the install hint.
// The build compiles with VK_NO_PROTOTYPES; every Vulkan call goes through api(), the table of
// the functions vk_reference uses. $RASTERCMP_VULKAN_LOADER replaces the file name
// libvulkan.so.1 (docs/reliability.md); the tests point it at a missing file.
#pragma once

#include <vulkan/vulkan.h>

namespace rastercmp::vk {

// What to install when there is no usable Vulkan loader or driver.
inline constexpr const char* kInstallVulkanHint =
    "install the Vulkan loader and lavapipe: apt-get install libvulkan1 mesa-vulkan-drivers";

// The environment variable that names the loader library instead of libvulkan.so.1.
inline constexpr const char* kLoaderEnv = "RASTERCMP_VULKAN_LOADER";

// Commands queried with vkGetInstanceProcAddr(NULL, ...) (the global commands).
#define RASTERCMP_VK_GLOBAL_COMMANDS(X) \
  X(vkCreateInstance)                   \
  X(vkEnumerateInstanceLayerProperties) \
  X(vkEnumerateInstanceVersion)

// Core 1.0/1.1 commands, taken from the loader's exported dispatching entry points (the same
// functions a link against libvulkan.so.1 resolves to, valid for every instance and device).
#define RASTERCMP_VK_CORE_COMMANDS(X)         \
  X(vkAllocateCommandBuffers)                 \
  X(vkAllocateDescriptorSets)                 \
  X(vkAllocateMemory)                         \
  X(vkBeginCommandBuffer)                     \
  X(vkBindBufferMemory)                       \
  X(vkBindImageMemory)                        \
  X(vkCmdBeginRenderPass)                     \
  X(vkCmdBindDescriptorSets)                  \
  X(vkCmdBindIndexBuffer)                     \
  X(vkCmdBindPipeline)                        \
  X(vkCmdBindVertexBuffers)                   \
  X(vkCmdCopyImageToBuffer)                   \
  X(vkCmdCopyBufferToImage)                   \
  X(vkCmdDispatch)                            \
  X(vkCmdDraw)                                \
  X(vkCmdDrawIndexed)                         \
  X(vkCmdEndRenderPass)                       \
  X(vkCmdPipelineBarrier)                     \
  X(vkCmdPushConstants)                       \
  X(vkCmdSetScissor)                          \
  X(vkCmdSetDepthBias)                        \
  X(vkCmdSetViewport)                         \
  X(vkCreateBuffer)                           \
  X(vkCreateCommandPool)                      \
  X(vkCreateComputePipelines)                 \
  X(vkCreateDescriptorPool)                   \
  X(vkCreateDescriptorSetLayout)              \
  X(vkCreateDevice)                           \
  X(vkCreateFence)                            \
  X(vkCreateFramebuffer)                      \
  X(vkCreateGraphicsPipelines)                \
  X(vkCreateImage)                            \
  X(vkCreateImageView)                        \
  X(vkCreatePipelineLayout)                   \
  X(vkCreateRenderPass)                       \
  X(vkCreateSampler)                          \
  X(vkCreateShaderModule)                     \
  X(vkDestroyBuffer)                          \
  X(vkDestroyCommandPool)                     \
  X(vkDestroyDescriptorPool)                  \
  X(vkDestroyDescriptorSetLayout)             \
  X(vkDestroyDevice)                          \
  X(vkDestroyFence)                           \
  X(vkDestroyFramebuffer)                     \
  X(vkDestroyImage)                           \
  X(vkDestroyImageView)                       \
  X(vkDestroyInstance)                        \
  X(vkDestroyPipeline)                        \
  X(vkDestroyPipelineLayout)                  \
  X(vkDestroyRenderPass)                      \
  X(vkDestroySampler)                         \
  X(vkDestroyShaderModule)                    \
  X(vkEndCommandBuffer)                       \
  X(vkEnumerateDeviceExtensionProperties)     \
  X(vkEnumeratePhysicalDevices)               \
  X(vkFreeCommandBuffers)                     \
  X(vkFreeMemory)                             \
  X(vkGetBufferMemoryRequirements)            \
  X(vkGetDeviceQueue)                         \
  X(vkGetImageMemoryRequirements)             \
  X(vkGetPhysicalDeviceFeatures2)             \
  X(vkGetPhysicalDeviceFormatProperties)      \
  X(vkGetPhysicalDeviceImageFormatProperties) \
  X(vkGetPhysicalDeviceMemoryProperties)      \
  X(vkGetPhysicalDeviceProperties)            \
  X(vkGetPhysicalDeviceProperties2)           \
  X(vkGetPhysicalDeviceQueueFamilyProperties) \
  X(vkMapMemory)                              \
  X(vkQueueSubmit)                            \
  X(vkResetFences)                            \
  X(vkUpdateDescriptorSets)                   \
  X(vkWaitForFences)

// The dispatch table: one pointer per command. vkEnumerateInstanceVersion is null under a
// Vulkan 1.0 loader; every other member is set.
struct Api {
  PFN_vkGetInstanceProcAddr vkGetInstanceProcAddr = nullptr;
#define RASTERCMP_VK_MEMBER(name) PFN_##name name = nullptr;
  RASTERCMP_VK_GLOBAL_COMMANDS(RASTERCMP_VK_MEMBER)
  RASTERCMP_VK_CORE_COMMANDS(RASTERCMP_VK_MEMBER)
#undef RASTERCMP_VK_MEMBER
};

// The table, loaded on the first call (thread-safe) and kept for the life of the process (the
// library is never closed: the driver's allocations stay reachable and its frames symbolized).
// Throws EnvironmentError naming the library and the hint when it cannot be opened or lacks a
// command; a later call tries again.
const Api& api();

}  // namespace rastercmp::vk
