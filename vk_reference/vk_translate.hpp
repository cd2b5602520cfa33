// The scene model's API-neutral enums → Vulkan enums. Pure functions; the only place where
// the two vocabularies meet (one module translates between the two vocabularies).
#pragma once

#include <vulkan/vulkan.h>

#include "model/scene.hpp"

namespace rastercmp::vk {

// The owner attachment: one uint32 owner id per sample (model/render_result.hpp).
inline constexpr VkFormat kOwnerFormat = VK_FORMAT_R32_UINT;

VkFormat to_vk_format(DepthFormat format);  // VK_FORMAT_UNDEFINED for None
VkPrimitiveTopology to_vk(Topology topology);
VkCullModeFlags to_vk(CullMode mode);
VkFrontFace to_vk(FrontFace face);
VkPolygonMode to_vk(PolygonMode mode);
VkCompareOp to_vk(CompareOp op);
VkLineRasterizationModeEXT to_vk(LineMode mode);
VkSampleCountFlagBits to_vk_samples(uint32_t samples);  // throws NotSupportedError if not 1,2,4,..64

// Bytes per texel that vkCmdCopyImageToBuffer writes for the depth aspect of `format`.
uint32_t depth_copy_texel_bytes(DepthFormat format);

// One texel of a depth-aspect copy → the raw stored bits (model/render_result.hpp depth_raw):
// D16 zero-extended, X8_D24 the low 24 bits (the top 8 are undefined), D32 the float bits.
uint32_t depth_raw_from_copy(DepthFormat format, const unsigned char* texel);

// How a device turns a stored UNORM depth value r of n bits into the float a shader samples. The
// spec fixes the value, f = r / (2^n - 1) ("Conversion from Normalized Fixed-Point to
// Floating-Point"), not its float rounding; the reference measures which of these a device does
// (vk_gather.hpp measure_unorm_sampling) and inverts that one.
enum class UnormSampling {
  Quotient,           // float(r / (2^n - 1)), correctly rounded: NVIDIA (H200, driver 580)
  ReciprocalProduct,  // float(r) * float(1 / (2^n - 1)), one float multiply: llvmpipe
                      // (lp_build_unsigned_norm_to_float)
};
inline constexpr UnormSampling kUnormSamplings[] = {UnormSampling::Quotient, UnormSampling::ReciprocalProduct};
const char* to_string(UnormSampling sampling);

// The float `sampling` gives for the raw value `raw` of an UNORM format whose largest value is `max`.
float sampled_unorm(UnormSampling sampling, uint32_t raw, uint32_t max);

// The float that sampling a depth texel returns → the raw stored bits. D32: the float's bits.
// UNORM: the raw r that `sampling` converts to that float. Quotient is one-to-one for D16 and
// X8_D24. ReciprocalProduct is one-to-one for D16; for X8_D24 it is one-to-one except that
// 0xFFFFFE and 0xFFFFFF both give 1.0, read back as 0xFFFFFF (the clear value 1.0's bits).
// Throws std::runtime_error for a float that no raw value converts to.
uint32_t depth_raw_from_sampled(DepthFormat format, UnormSampling sampling, uint32_t float_bits);

VkViewport to_vk(const Viewport& viewport);

// Vulkan forbids negative scissor offsets (VUID-vkCmdSetScissor-x-00595). The part of the
// rectangle left of x = 0 or above y = 0 covers no pixel, so it is cut off; what remains selects
// the same pixels (lavapipe draws framebuffer ∩ scissor, docs/lavapipe-rules.md §2.5).
VkRect2D to_vk_scissor(const Rect2D& scissor);

}  // namespace rastercmp::vk
