// A misbehaving Vulkan "driver" for the runner's tests: an explicit Vulkan layer
// (VK_LAYER_RASTERCMP_hostile) that sits between rastercmp and lavapipe and, on the scenes it is
// told to, does in the driver's place what real drivers do when they go wrong. Test-only: built in
// the test tree, enabled by VK_LAYER_PATH and VK_INSTANCE_LAYERS (tests/test_cli_hostile_driver.cpp).
//
// RASTERCMP_HOSTILE_LAYER=FAULT:WIDTH arms the fault when an image WIDTH pixels wide is created
// (the scene of that width); it fires in the next vkQueueSubmit, once per process. FAULT is one of
//   segv            a store through a null pointer
//   abort           abort()
//   exit2           _exit(2): the process ends with the status the runner uses for bad input
//   hang            sleeps for ever inside the submit
//   stop            raise(SIGSTOP)
//   device_lost     returns VK_ERROR_DEVICE_LOST
//   stray_line      writes a line into every pipe the process holds
//   helper          forks a process that inherits every descriptor and sleeps for ever (a crash
//                   handler, a cache daemon); its pid goes to RASTERCMP_HOSTILE_DIR/helper.pid
//   close_fds_hang  closes every descriptor, then sleeps for ever
//   stderr_flood    writes 32 MiB to stderr, then submits
// Anything else is reported on stderr and ignored (the layer passes everything through).
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <mutex>
#include <string>
#include <unordered_map>

#include <vulkan/vk_layer.h>
#include <vulkan/vulkan.h>

#define HOSTILE_EXPORT extern "C" __attribute__((visibility("default")))

namespace {

struct InstanceTable {
  PFN_vkGetInstanceProcAddr next_gipa = nullptr;
  PFN_vkDestroyInstance destroy = nullptr;
};

struct DeviceTable {
  PFN_vkGetDeviceProcAddr next_gdpa = nullptr;
  PFN_vkDestroyDevice destroy = nullptr;
  PFN_vkCreateImage create_image = nullptr;
  PFN_vkQueueSubmit queue_submit = nullptr;
};

// Dispatchable handles (instance; device and its queues) start with the loader's table pointer.
void* key_of(const void* handle) { return *static_cast<void* const*>(handle); }

std::mutex tables_mutex;
std::unordered_map<void*, InstanceTable> instances;
std::unordered_map<void*, DeviceTable> devices;

struct Fault {
  std::string kind;
  uint32_t width = 0;
};

Fault configured_fault() {
  Fault fault;
  const char* value = std::getenv("RASTERCMP_HOSTILE_LAYER");
  if (value == nullptr) return fault;
  const std::string text = value;
  const auto colon = text.find(':');
  if (colon == std::string::npos) return fault;
  fault.kind = text.substr(0, colon);
  fault.width = uint32_t(std::strtoul(text.c_str() + colon + 1, nullptr, 10));
  return fault;
}

std::mutex fault_mutex;
bool armed = false, fired = false;

void sleep_for_ever() {
  for (;;) pause();
}

void write_text(int fd, const char* text) {
  const ssize_t ignored = ::write(fd, text, std::strlen(text));
  (void)ignored;
}

// The fault in the driver's place; returns the VkResult the submit gives when it returns at all.
VkResult misbehave(const std::string& kind) {
  if (kind == "segv") {
    signal(SIGSEGV, SIG_DFL);  // a plain death, also under a sanitizer's handler
    *static_cast<volatile int*>(nullptr) = 1;
  } else if (kind == "abort") {
    signal(SIGABRT, SIG_DFL);
    std::abort();
  } else if (kind == "exit2") {
    _exit(2);  // not exit(): a leak check at exit would change the status under a sanitizer
  } else if (kind == "hang") {
    sleep_for_ever();
  } else if (kind == "stop") {
    raise(SIGSTOP);
  } else if (kind == "device_lost") {
    return VK_ERROR_DEVICE_LOST;
  } else if (kind == "stray_line") {
    for (int fd = 3; fd < 1024; ++fd) {
      struct stat st{};
      if (fstat(fd, &st) == 0 && S_ISFIFO(st.st_mode)) write_text(fd, "hostile driver was here\n");
    }
  } else if (kind == "helper") {
    const pid_t helper = fork();
    if (helper == 0) sleep_for_ever();
    if (const char* dir = std::getenv("RASTERCMP_HOSTILE_DIR"))
      std::ofstream(std::string(dir) + "/helper.pid") << helper << "\n";
  } else if (kind == "close_fds_hang") {
    for (int fd = 0; fd < 1024; ++fd) close(fd);
    sleep_for_ever();
  } else if (kind == "stderr_flood") {
    const std::string block(1 << 20, 'x');
    for (int i = 0; i < 32; ++i) {
      const ssize_t ignored = ::write(2, block.data(), block.size());
      (void)ignored;
    }
  } else {
    std::fprintf(stderr, "hostile layer: unknown fault \"%s\", ignored\n", kind.c_str());
  }
  return VK_SUCCESS;
}

VKAPI_ATTR VkResult VKAPI_CALL hostile_CreateImage(VkDevice device, const VkImageCreateInfo* info,
                                                   const VkAllocationCallbacks* allocator, VkImage* image) {
  PFN_vkCreateImage next = nullptr;
  {
    const std::lock_guard<std::mutex> lock(tables_mutex);
    next = devices.at(key_of(device)).create_image;
  }
  const Fault fault = configured_fault();
  if (!fault.kind.empty() && info->extent.width == fault.width) {
    const std::lock_guard<std::mutex> lock(fault_mutex);
    armed = !fired;
  }
  return next(device, info, allocator, image);
}

VKAPI_ATTR VkResult VKAPI_CALL hostile_QueueSubmit(VkQueue queue, uint32_t count, const VkSubmitInfo* submits,
                                                   VkFence fence) {
  PFN_vkQueueSubmit next = nullptr;
  {
    const std::lock_guard<std::mutex> lock(tables_mutex);
    next = devices.at(key_of(queue)).queue_submit;
  }
  bool fire = false;
  {
    const std::lock_guard<std::mutex> lock(fault_mutex);
    fire = armed && !fired;
    if (fire) fired = true, armed = false;
  }
  if (fire) {
    const VkResult result = misbehave(configured_fault().kind);
    if (result != VK_SUCCESS) return result;
  }
  return next(queue, count, submits, fence);
}

// The loader's link in a create info's chain (VkLayerInstanceCreateInfo or VkLayerDeviceCreateInfo
// of sType `type` and function VK_LAYER_LINK_INFO), or null.
template <typename LinkInfo>
LinkInfo* layer_link(const void* next, VkStructureType type) {
  auto* link = static_cast<LinkInfo*>(const_cast<void*>(next));
  while (link != nullptr && !(link->sType == type && link->function == VK_LAYER_LINK_INFO))
    link = static_cast<LinkInfo*>(const_cast<void*>(link->pNext));
  return link;
}

// Removes the table of `handle` and returns its destroy function.
template <typename Table, typename Handle>
auto take_destroy(std::unordered_map<void*, Table>& tables, Handle handle) {
  const std::lock_guard<std::mutex> lock(tables_mutex);
  const auto it = tables.find(key_of(handle));
  const auto destroy = it->second.destroy;
  tables.erase(it);
  return destroy;
}

VKAPI_ATTR VkResult VKAPI_CALL hostile_CreateInstance(const VkInstanceCreateInfo* info,
                                                      const VkAllocationCallbacks* allocator, VkInstance* instance) {
  auto* link = layer_link<VkLayerInstanceCreateInfo>(info->pNext, VK_STRUCTURE_TYPE_LOADER_INSTANCE_CREATE_INFO);
  if (link == nullptr) return VK_ERROR_INITIALIZATION_FAILED;
  const PFN_vkGetInstanceProcAddr next_gipa = link->u.pLayerInfo->pfnNextGetInstanceProcAddr;
  link->u.pLayerInfo = link->u.pLayerInfo->pNext;
  const auto create = reinterpret_cast<PFN_vkCreateInstance>(next_gipa(VK_NULL_HANDLE, "vkCreateInstance"));
  const VkResult result = create(info, allocator, instance);
  if (result != VK_SUCCESS) return result;
  InstanceTable table;
  table.next_gipa = next_gipa;
  table.destroy = reinterpret_cast<PFN_vkDestroyInstance>(next_gipa(*instance, "vkDestroyInstance"));
  const std::lock_guard<std::mutex> lock(tables_mutex);
  instances[key_of(*instance)] = table;
  return VK_SUCCESS;
}

VKAPI_ATTR void VKAPI_CALL hostile_DestroyInstance(VkInstance instance, const VkAllocationCallbacks* allocator) {
  take_destroy(instances, instance)(instance, allocator);
}

VKAPI_ATTR VkResult VKAPI_CALL hostile_CreateDevice(VkPhysicalDevice physical, const VkDeviceCreateInfo* info,
                                                    const VkAllocationCallbacks* allocator, VkDevice* device) {
  auto* link = layer_link<VkLayerDeviceCreateInfo>(info->pNext, VK_STRUCTURE_TYPE_LOADER_DEVICE_CREATE_INFO);
  if (link == nullptr) return VK_ERROR_INITIALIZATION_FAILED;
  const PFN_vkGetInstanceProcAddr next_gipa = link->u.pLayerInfo->pfnNextGetInstanceProcAddr;
  const PFN_vkGetDeviceProcAddr next_gdpa = link->u.pLayerInfo->pfnNextGetDeviceProcAddr;
  link->u.pLayerInfo = link->u.pLayerInfo->pNext;
  const auto create = reinterpret_cast<PFN_vkCreateDevice>(next_gipa(VK_NULL_HANDLE, "vkCreateDevice"));
  const VkResult result = create(physical, info, allocator, device);
  if (result != VK_SUCCESS) return result;
  DeviceTable table;
  table.next_gdpa = next_gdpa;
  table.destroy = reinterpret_cast<PFN_vkDestroyDevice>(next_gdpa(*device, "vkDestroyDevice"));
  table.create_image = reinterpret_cast<PFN_vkCreateImage>(next_gdpa(*device, "vkCreateImage"));
  table.queue_submit = reinterpret_cast<PFN_vkQueueSubmit>(next_gdpa(*device, "vkQueueSubmit"));
  const std::lock_guard<std::mutex> lock(tables_mutex);
  devices[key_of(*device)] = table;
  return VK_SUCCESS;
}

VKAPI_ATTR void VKAPI_CALL hostile_DestroyDevice(VkDevice device, const VkAllocationCallbacks* allocator) {
  take_destroy(devices, device)(device, allocator);
}

PFN_vkVoidFunction own_device_function(const char* name) {
  if (std::strcmp(name, "vkGetDeviceProcAddr") == 0) return nullptr;  // handled by the caller
  if (std::strcmp(name, "vkDestroyDevice") == 0) return reinterpret_cast<PFN_vkVoidFunction>(hostile_DestroyDevice);
  if (std::strcmp(name, "vkCreateImage") == 0) return reinterpret_cast<PFN_vkVoidFunction>(hostile_CreateImage);
  if (std::strcmp(name, "vkQueueSubmit") == 0) return reinterpret_cast<PFN_vkVoidFunction>(hostile_QueueSubmit);
  return nullptr;
}

}  // namespace

HOSTILE_EXPORT VKAPI_ATTR PFN_vkVoidFunction VKAPI_CALL vkGetDeviceProcAddr(VkDevice device, const char* name);

HOSTILE_EXPORT VKAPI_ATTR PFN_vkVoidFunction VKAPI_CALL vkGetInstanceProcAddr(VkInstance instance, const char* name) {
  if (std::strcmp(name, "vkGetInstanceProcAddr") == 0)
    return reinterpret_cast<PFN_vkVoidFunction>(vkGetInstanceProcAddr);
  if (std::strcmp(name, "vkGetDeviceProcAddr") == 0) return reinterpret_cast<PFN_vkVoidFunction>(vkGetDeviceProcAddr);
  if (std::strcmp(name, "vkCreateInstance") == 0) return reinterpret_cast<PFN_vkVoidFunction>(hostile_CreateInstance);
  if (std::strcmp(name, "vkDestroyInstance") == 0)
    return reinterpret_cast<PFN_vkVoidFunction>(hostile_DestroyInstance);
  if (std::strcmp(name, "vkCreateDevice") == 0) return reinterpret_cast<PFN_vkVoidFunction>(hostile_CreateDevice);
  if (PFN_vkVoidFunction own = own_device_function(name)) return own;
  if (instance == VK_NULL_HANDLE) return nullptr;
  PFN_vkGetInstanceProcAddr next = nullptr;
  {
    const std::lock_guard<std::mutex> lock(tables_mutex);
    const auto it = instances.find(key_of(instance));
    if (it == instances.end()) return nullptr;
    next = it->second.next_gipa;
  }
  return next(instance, name);
}

HOSTILE_EXPORT VKAPI_ATTR PFN_vkVoidFunction VKAPI_CALL vkGetDeviceProcAddr(VkDevice device, const char* name) {
  if (std::strcmp(name, "vkGetDeviceProcAddr") == 0) return reinterpret_cast<PFN_vkVoidFunction>(vkGetDeviceProcAddr);
  if (PFN_vkVoidFunction own = own_device_function(name)) return own;
  PFN_vkGetDeviceProcAddr next = nullptr;
  {
    const std::lock_guard<std::mutex> lock(tables_mutex);
    const auto it = devices.find(key_of(device));
    if (it == devices.end()) return nullptr;
    next = it->second.next_gdpa;
  }
  return next(device, name);
}
