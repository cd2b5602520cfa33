#include "compare/case_record.hpp"

#include "compare/depth_units.hpp"
#include "model/depth_format.hpp"
#include "model/errors.hpp"

namespace rastercmp {
namespace {

using OJson = nlohmann::ordered_json;
using Json = nlohmann::json;

OJson location_json(const SampleLocation& at) { return OJson{{"x", at.x}, {"y", at.y}, {"sample", at.sample}}; }

OJson bad_sample_json(const BadSample& b) {
  OJson j = location_json(b.at);
  j["kind"] = b.kind;
  j["expected_owner"] = b.expected_owner;
  j["actual_owner"] = b.actual_owner;
  if (b.has_depth) {
    j["expected_depth_raw"] = b.expected_depth_raw;
    j["actual_depth_raw"] = b.actual_depth_raw;
    j["depth_diff"] = b.depth_diff_raw;
    j["depth_diff_r"] = b.depth_diff_r;
  }
  return j;
}

void add_diff_fields(OJson& j, const DiffSummary* d) {
  auto put = [&](const char* key, auto value) { j[key] = d ? OJson(value) : OJson(nullptr); };
  put("samples", d ? d->samples : 0);
  put("depth_format", d ? to_string(d->depth_format) : "");
  put("depth_compared", d ? d->depth_compared : false);
  put("coverage_mismatches", d ? d->coverage_mismatches() : 0);
  put("missing", d ? d->missing : 0);
  put("unexpected", d ? d->unexpected : 0);
  put("wrong_owner", d ? d->wrong_owner : 0);
  put("allowed", d ? d->allowed : 0);
  put("allowed_owner", d ? d->allowed_owner : 0);
  put("covered_match", d ? d->covered_match : 0);
  put("bad_pixels", d ? d->bad_pixels : 0);
  put("depth_mismatches", d ? d->depth.mismatches : 0);
  put("depth_unit", d ? (d->depth_compared ? depth_unit_name(d->depth_format) : "") : "");
  put("max_depth_error", d ? d->depth.max_raw : 0);
  put("max_depth_error_r", d ? d->depth.max_r : 0.0);
  put("depth_p50", d ? d->depth.p50_raw : 0);
  put("depth_p95", d ? d->depth.p95_raw : 0);
  put("depth_p50_r", d ? d->depth.p50_r : 0.0);
  put("depth_p95_r", d ? d->depth.p95_r : 0.0);
  put("depth_intervals_checked", d ? d->depth_intervals_checked : false);
  put("depth_outside", d ? d->depth_outside : 0);
  if (d && d->depth_outside != 0) {
    OJson v = location_json(d->worst_outside.at);
    v["actual_raw"] = d->worst_outside.actual_raw;
    v["bound"] = d->worst_outside.above ? "hi" : "lo";
    v["bound_raw"] = d->worst_outside.bound_raw;
    v["distance"] = d->worst_outside.distance;
    v["term"] = to_string(d->worst_outside.term);
    j["depth_outside_at"] = v;
  } else {
    j["depth_outside_at"] = nullptr;
  }
  if (d) {
    OJson at = location_json(d->depth.max_at);
    at["expected_raw"] = d->depth.max_expected_raw;
    at["actual_raw"] = d->depth.max_actual_raw;
    j["max_depth_at"] = at;
    OJson bad = OJson::array();
    for (const BadSample& b : d->first_bad) bad.push_back(bad_sample_json(b));
    j["first_bad"] = bad;
  } else {
    j["max_depth_at"] = nullptr;
    j["first_bad"] = nullptr;
  }
}

// Reading back, with the JSON path of the field in every error.
struct Reader {
  const std::string& file;

  const Json& at(const Json& obj, const std::string& path, const char* key) const {
    if (!obj.is_object() || !obj.contains(key)) throw InputError(file, path + "." + key, "expected the field");
    return obj.at(key);
  }
  template <typename T>
  T get(const Json& obj, const std::string& path, const char* key) const {
    const Json& v = at(obj, path, key);
    try {
      return v.get<T>();
    } catch (const nlohmann::json::exception& e) {
      throw InputError(file, path + "." + key, std::string("expected a value of the right type: ") + e.what());
    }
  }
  SampleLocation location(const Json& obj, const std::string& path) const {
    return {get<uint32_t>(obj, path, "x"), get<uint32_t>(obj, path, "y"), get<uint32_t>(obj, path, "sample")};
  }
};

DepthFormat parse_depth_format(const Reader& r, const Json& obj, const std::string& path) {
  const std::string name = r.get<std::string>(obj, path, "depth_format");
  for (DepthFormat f : kAllDepthFormats)
    if (name == to_string(f)) return f;
  throw InputError(r.file, path + ".depth_format", "expected a depth format name, found " + name);
}

BadSample bad_sample_from_json(const Reader& r, const Json& j, const std::string& path) {
  BadSample b;
  b.at = r.location(j, path);
  b.kind = r.get<std::string>(j, path, "kind");
  b.expected_owner = r.get<uint32_t>(j, path, "expected_owner");
  b.actual_owner = r.get<uint32_t>(j, path, "actual_owner");
  b.has_depth = j.contains("expected_depth_raw");
  if (b.has_depth) {
    b.expected_depth_raw = r.get<uint32_t>(j, path, "expected_depth_raw");
    b.actual_depth_raw = r.get<uint32_t>(j, path, "actual_depth_raw");
    b.depth_diff_raw = r.get<uint64_t>(j, path, "depth_diff");
    b.depth_diff_r = r.get<double>(j, path, "depth_diff_r");
  }
  return b;
}

DiffSummary diff_from_json(const Reader& r, const Json& j, const std::string& path, CompareProfile profile) {
  DiffSummary d;
  d.profile = profile;
  d.width = r.get<uint32_t>(j, path, "width");
  d.height = r.get<uint32_t>(j, path, "height");
  d.samples = r.get<uint32_t>(j, path, "samples");
  d.depth_format = parse_depth_format(r, j, path);
  d.depth_compared = r.get<bool>(j, path, "depth_compared");
  d.pixels = r.get<uint64_t>(j, path, "pixels");
  d.samples_compared = d.pixels * d.samples;
  d.missing = r.get<uint64_t>(j, path, "missing");
  d.unexpected = r.get<uint64_t>(j, path, "unexpected");
  d.wrong_owner = r.get<uint64_t>(j, path, "wrong_owner");
  d.allowed = r.get<uint64_t>(j, path, "allowed");
  if (j.contains("allowed_owner"))  // records written before the owner alternatives lack it
    d.allowed_owner = r.get<uint64_t>(j, path, "allowed_owner");
  d.covered_match = r.get<uint64_t>(j, path, "covered_match");
  d.bad_pixels = r.get<uint64_t>(j, path, "bad_pixels");
  d.depth.mismatches = r.get<uint64_t>(j, path, "depth_mismatches");
  d.depth.max_raw = r.get<uint64_t>(j, path, "max_depth_error");
  d.depth.max_r = r.get<double>(j, path, "max_depth_error_r");
  d.depth.p50_raw = r.get<uint64_t>(j, path, "depth_p50");
  d.depth.p95_raw = r.get<uint64_t>(j, path, "depth_p95");
  d.depth.p50_r = r.get<double>(j, path, "depth_p50_r");
  d.depth.p95_r = r.get<double>(j, path, "depth_p95_r");
  const Json& at = r.at(j, path, "max_depth_at");
  d.depth.max_at = r.location(at, path + ".max_depth_at");
  d.depth.max_expected_raw = r.get<uint32_t>(at, path + ".max_depth_at", "expected_raw");
  d.depth.max_actual_raw = r.get<uint32_t>(at, path + ".max_depth_at", "actual_raw");
  if (j.contains("depth_outside")) {  // records written before the depth intervals lack them
    d.depth_intervals_checked = r.get<bool>(j, path, "depth_intervals_checked");
    d.depth_outside = r.get<uint64_t>(j, path, "depth_outside");
  }
  if (d.depth_outside != 0) {
    const std::string vpath = path + ".depth_outside_at";
    const Json& v = r.at(j, path, "depth_outside_at");
    d.worst_outside.at = r.location(v, vpath);
    d.worst_outside.actual_raw = r.get<uint32_t>(v, vpath, "actual_raw");
    d.worst_outside.above = r.get<std::string>(v, vpath, "bound") == "hi";
    d.worst_outside.bound_raw = r.get<uint32_t>(v, vpath, "bound_raw");
    d.worst_outside.distance = r.get<uint64_t>(v, vpath, "distance");
    const std::string term = r.get<std::string>(v, vpath, "term");
    for (DepthTerm t : {DepthTerm::Plane, DepthTerm::Snapping, DepthTerm::Bias, DepthTerm::Precision,
                        DepthTerm::Rounding, DepthTerm::Clear, DepthTerm::Undefined})
      if (term == to_string(t)) d.worst_outside.term = t;
  }
  const Json& bad = r.at(j, path, "first_bad");
  for (size_t i = 0; i < bad.size(); ++i)
    d.first_bad.push_back(bad_sample_from_json(r, bad[i], path + ".first_bad[" + std::to_string(i) + "]"));
  return d;
}

}  // namespace

nlohmann::ordered_json case_to_json(const CaseRecord& c, bool with_outcome) {
  OJson j;
  j["scene"] = c.name;
  j["source"] = c.source;
  j["cpu_method"] = c.cpu_method;
  j["verdict"] = to_string(c.verdict);
  j["message"] = c.message;
  j["compared"] = c.diff.has_value();
  j["profile"] = c.diff ? OJson(to_string(c.diff->profile)) : OJson(nullptr);
  j["width"] = c.width;
  j["height"] = c.height;
  j["pixels"] = uint64_t(c.width) * c.height;
  add_diff_fields(j, c.diff ? &*c.diff : nullptr);
  if (!with_outcome) return j;
  j["expectation"] = c.expectation;
  j["expectation_reason"] = c.expectation_reason;
  j["status"] = c.status;
  j["fails_run"] = c.fails_run;
  j["images"] = {{"cpu", c.images.cpu},
                 {"vulkan", c.images.vulkan},
                 {"mask", c.images.mask},
                 {"depth_heatmap", c.images.depth_heatmap}};
  OJson explains = OJson::array();
  for (const ExplainLink& e : c.explains) {
    OJson link = location_json(e.at);
    link["file"] = e.file;
    explains.push_back(link);
  }
  j["explains"] = explains;
  return j;
}

CaseRecord case_from_json(const nlohmann::json& j, const std::string& file, const std::string& path) {
  const Reader r{file};
  CaseRecord c;
  c.name = r.get<std::string>(j, path, "scene");
  c.source = r.get<std::string>(j, path, "source");
  c.cpu_method = r.get<std::string>(j, path, "cpu_method");
  const std::string verdict = r.get<std::string>(j, path, "verdict");
  const std::string expectation = r.get<std::string>(j, path, "expectation");
  if (!parse_verdict(verdict)) throw InputError(file, path + ".verdict", "expected a CTS result name");
  c.verdict = *parse_verdict(verdict);
  c.expectation = expectation;
  c.message = r.get<std::string>(j, path, "message");
  c.width = r.get<uint32_t>(j, path, "width");
  c.height = r.get<uint32_t>(j, path, "height");
  if (r.get<bool>(j, path, "compared")) {
    const std::string profile = r.get<std::string>(j, path, "profile");
    c.diff = diff_from_json(r, j, path, profile == "spec" ? CompareProfile::Spec : CompareProfile::Lavapipe);
  }
  c.expectation_reason = r.get<std::string>(j, path, "expectation_reason");
  c.status = r.get<std::string>(j, path, "status");
  c.fails_run = r.get<bool>(j, path, "fails_run");
  const Json& images = r.at(j, path, "images");
  c.images.cpu = r.get<std::string>(images, path + ".images", "cpu");
  c.images.vulkan = r.get<std::string>(images, path + ".images", "vulkan");
  c.images.mask = r.get<std::string>(images, path + ".images", "mask");
  c.images.depth_heatmap = r.get<std::string>(images, path + ".images", "depth_heatmap");
  const Json& explains = r.at(j, path, "explains");
  for (size_t i = 0; i < explains.size(); ++i) {
    const std::string p = path + ".explains[" + std::to_string(i) + "]";
    c.explains.push_back({r.location(explains[i], p), r.get<std::string>(explains[i], p, "file")});
  }
  return c;
}

}  // namespace rastercmp
