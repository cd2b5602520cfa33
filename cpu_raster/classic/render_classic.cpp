#include "cpu_raster/classic/render_classic.hpp"

#include <optional>
#include <string>
#include <vector>

#include "cpu_raster/classic/classic_front_end.hpp"
#include "cpu_raster/classic/classic_visibility.hpp"
#include "cpu_raster/classic/method_registry.hpp"
#include "cpu_raster/exact/float_ops.hpp"
#include "cpu_raster/exact/profile_support.hpp"
#include "cpu_raster/exact/render_targets.hpp"
#include "model/errors.hpp"

namespace rastercmp {
namespace {

using namespace cpu::classic;

void check_classic_support(const Scene& scene, const CpuOptions& options) {
  if (options.profile != CpuProfile::Lavapipe)
    throw NotSupportedError("classic methods (--method) run on the lavapipe profile only");
  for (const MethodChoice& choice : options.methods)
    if (const std::optional<std::string> why = method_inapplicable(scene, choice)) throw NotSupportedError(*why);
}

std::string describe_methods(const CpuOptions& options) {
  std::string text = lavapipe_profile_device(options) + ", methods";
  for (const MethodChoice& choice : options.methods) text += " " + choice.stage + "=" + choice.name;
  return text;
}

void write_fragment(const Fragment& f, const ClassicPrimitive& p, bool test, cpu::RenderTargets& targets) {
  const size_t i = targets.index(f.x, f.y, 0);
  if (p.depth.active && test && !cpu::depth_test_passes(p.depth.op, p.depth.format, f.depth_raw, targets.depth_raw[i]))
    return;
  if (p.depth.write) targets.depth_raw[i] = f.depth_raw;
  targets.owner[i] = p.raster.owner;
}

// visibility=zbuffer: primitives in order through the depth test (docs/lavapipe-rules.md §3.6).
void draw_with_zbuffer(const std::vector<ClassicPrimitive>& primitives, const ClassicMethods& chosen,
                       const cpu::PixelRect& region, cpu::RenderTargets& targets) {
  for (const ClassicPrimitive& p : primitives) {
    if (!chosen.per_pixel()) {  // the exact rasterizer, with the depth evaluation fused or not
      cpu::DepthTestState depth = p.depth;
      if (chosen.depth == DepthMethod::NoFma) depth.fma = false;
      cpu::rasterize_primitive(p.raster, depth, targets);
      continue;
    }
    for_each_fragment(p, chosen, region, [&](const Fragment& f) { write_fragment(f, p, true, targets); });
  }
}

}  // namespace

bool uses_classic_methods(const CpuOptions& options) { return names_classic_stage(options.methods); }

namespace cpu::classic {

ClassicFrame prepare_classic_frame(const Scene& scene, const CpuOptions& options, bool keep_culled) {
  ClassicFrame prepared{parse_classic_methods(options.methods), {}, {}, {}};
  cpu::check_lavapipe_profile_support(scene);
  check_classic_support(scene, options);
  prepared.frame =
      cpu::make_frame_context(scene, options.fma, prepared.chosen.setup, cpu::WorkSkips{}, options.lavapipe->rules());
  for (uint32_t d = 0; d < scene.draws.size(); ++d)
    collect_primitives(prepared.frame, d, prepared.chosen, prepared.primitives,
                       keep_culled ? &prepared.culled : nullptr);
  return prepared;
}

}  // namespace cpu::classic

RenderResult render_classic(const Scene& scene, const CpuOptions& options) {
  const cpu::DenormalsFlushed ftz_daz;  // as render_exact: draw_vbo and the rasterizer threads (rules §7.10)
  const ClassicFrame prepared = prepare_classic_frame(scene, options);
  const ClassicMethods& chosen = prepared.chosen;
  const cpu::FrameContext& frame = prepared.frame;
  const std::vector<ClassicPrimitive>& primitives = prepared.primitives;
  cpu::RenderTargets targets = cpu::make_render_targets(scene);
  if (chosen.visibility == VisibilityMethod::ZBuffer) {
    draw_with_zbuffer(primitives, chosen, frame.region, targets);
  } else {
    for (const PaintedFragment& painted : back_to_front_fragments(primitives, chosen, frame.region))
      write_fragment(painted.fragment, primitives[painted.primitive], false, targets);
  }
  RenderResult result;
  cpu::move_into_result(std::move(targets), describe_methods(options), options.fma, result);
  return result;
}

}  // namespace rastercmp
