// The report's page per case and its bad-sample pages (compare/report.hpp).
#include <fmt/core.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <kainjow/mustache.hpp>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "compare/depth_units.hpp"
#include "compare/report.hpp"
#include "compare/report_template.hpp"
#include "model/image_io.hpp"

namespace rastercmp {
namespace fs = std::filesystem;
namespace {

using kainjow::mustache::data;
using kainjow::mustache::mustache;

std::string owner_short_text(uint32_t owner) {
  if (owner == kOwnerBackground) return "background";
  return fmt::format("draw {} prim {}", owner_draw(owner), owner_primitive(owner));
}

// A section that is left out when the text is empty (a non-empty string opens it).
data optional_text(const std::string& text) { return text.empty() ? data(false) : data(text); }

std::string render(std::string_view tmpl, const data& d, const char* what) {
  mustache page{std::string(tmpl)};
  if (!page.is_valid())
    throw std::runtime_error(fmt::format("the {} template does not parse: {}", what, page.error_message()));
  std::string html = page.render(d);
  if (!page.is_valid())
    throw std::runtime_error(fmt::format("the {} template did not render: {}", what, page.error_message()));
  return html;
}

// The renderers' names as the case judges them.
std::string judged_label(const std::string& cpu_method) {
  return cpu_is_judged(cpu_method) ? "CPU method " + cpu_method : "Vulkan device";
}
std::string reference_label(const std::string& cpu_method) {
  return cpu_is_judged(cpu_method) ? "Vulkan device" : "CPU model (exact)";
}

// One bad sample, reference and judged sides in place of the diff's expected (CPU) and actual
// (Vulkan).
data bad_sample_row(const BadSample& b, bool cpu_judged) {
  data d;
  d.set("x", std::to_string(b.at.x));
  d.set("y", std::to_string(b.at.y));
  d.set("sample", std::to_string(b.at.sample));
  d.set("kind", judged_kind(b.kind, cpu_judged));
  const uint32_t reference_owner = cpu_judged ? b.actual_owner : b.expected_owner;
  const uint32_t judged_owner = cpu_judged ? b.expected_owner : b.actual_owner;
  const uint32_t reference_depth = cpu_judged ? b.actual_depth_raw : b.expected_depth_raw;
  const uint32_t judged_depth = cpu_judged ? b.expected_depth_raw : b.actual_depth_raw;
  d.set("reference_owner", owner_short_text(reference_owner));
  d.set("judged_owner", owner_short_text(judged_owner));
  d.set("reference_depth", b.has_depth ? fmt::format("{:#x}", reference_depth) : "-");
  d.set("judged_depth", b.has_depth ? fmt::format("{:#x}", judged_depth) : "-");
  d.set("depth_diff", b.depth_diff_raw ? fmt::format("{} ({} r)", b.depth_diff_raw, report_number(b.depth_diff_r)) : "-");
  return d;
}

// A file's text, or "" with `error` set when it cannot be read.
std::string read_file(const fs::path& path, std::string& error) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    error = "could not be read when the report was written";
    return {};
  }
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// A path relative to the report folder, as seen from the case's folder.
std::string from_case_folder(const std::string& path, const std::string& folder) {
  if (path.rfind(folder + "/", 0) == 0) return path.substr(folder.size() + 1);
  return "../../" + path;
}

void set_numbers(data& d, const DiffSummary& s, bool cpu_judged) {
  d.set("samples", std::to_string(s.samples));
  d.set("depth_format", to_string(s.depth_format));
  d.set("pixels", std::to_string(s.pixels));
  d.set("bad_pixels", std::to_string(s.bad_pixels));
  d.set("covered_match", std::to_string(s.covered_match));
  d.set("lacks", std::to_string(cpu_judged ? s.unexpected : s.missing));
  d.set("adds", std::to_string(cpu_judged ? s.missing : s.unexpected));
  d.set("wrong_owner", std::to_string(s.wrong_owner));
  d.set("allowed", std::to_string(s.allowed));
  d.set("allowed_owner", std::to_string(s.allowed_owner));
  d.set("depth_mismatches", std::to_string(s.depth.mismatches));
  d.set("depth_unit", s.depth_compared ? depth_unit_name(s.depth_format) : "- (depth not compared)");
  d.set("depth_p50", std::to_string(s.depth.p50_raw));
  d.set("depth_p95", std::to_string(s.depth.p95_raw));
  d.set("max_depth", std::to_string(s.depth.max_raw));
  d.set("depth_p50_r", report_number(s.depth.p50_r));
  d.set("depth_p95_r", report_number(s.depth.p95_r));
  d.set("max_depth_r", report_number(s.depth.max_r));
  d.set("max_depth_at", fmt::format("({}, {}) sample {}", s.depth.max_at.x, s.depth.max_at.y, s.depth.max_at.sample));
}

void set_bad_samples(data& d, const CaseRecord& c, const std::string& folder, bool cpu_judged) {
  const DiffSummary& s = *c.diff;
  const uint64_t total = bad_sample_count(s);
  d.set("bad_total_zero", total == 0);
  d.set("has_bad", total != 0);
  d.set("bad_total", std::to_string(total));
  d.set("bad_shown", std::to_string(s.first_bad.size()));
  d.set("per_page", std::to_string(kBadSamplesPerPage));
  data pages{data::type::list};
  for (size_t n = 1; n <= bad_sample_pages(s); ++n) {
    data page;
    page.set("n", std::to_string(n));
    page.set("href", bad_samples_page(n));
    pages << page;
  }
  d.set("pages", pages);
  data bad{data::type::list};
  for (const BadSample& b : s.first_bad) {
    data row = bad_sample_row(b, cpu_judged);
    std::string link;
    for (const ExplainLink& e : c.explains)
      if (e.at == b.at) link = from_case_folder(e.file, folder);
    row.set("explain", optional_text(link));
    bad << row;
  }
  d.set("bad", bad);
}

void set_images(data& d, const CaseRecord& c, const std::string& folder, bool cpu_judged) {
  const std::string cpu = c.images.cpu.empty() ? "" : from_case_folder(c.images.cpu, folder);
  const std::string vulkan = c.images.vulkan.empty() ? "" : from_case_folder(c.images.vulkan, folder);
  d.set("reference_image", optional_text(cpu_judged ? vulkan : cpu));
  d.set("judged_image", optional_text(cpu_judged ? cpu : vulkan));
  d.set("mask_image", optional_text(c.images.mask.empty() ? "" : from_case_folder(c.images.mask, folder)));
  const std::string depth = c.images.depth_heatmap.empty() ? "" : from_case_folder(c.images.depth_heatmap, folder);
  d.set("depth_image", optional_text(depth));
  if (!depth.empty()) d.set("colour_bar", depth_colour_bar_css());
  const bool compared = c.diff.has_value();
  d.set("depth_identical", compared && c.diff->depth_compared && c.diff->depth.mismatches == 0);
  std::string uncompared;
  if (compared && !c.diff->depth_compared)
    uncompared = c.diff->depth_format == DepthFormat::None ? "the scene has no depth buffer"
                                                           : "one renderer returned no depth for this format";
  d.set("depth_uncompared", optional_text(uncompared));
  d.set("has_images", !cpu.empty() || !vulkan.empty());
}

void set_explains(data& d, const CaseRecord& c, const std::string& report_dir, const std::string& folder) {
  data list{data::type::list};
  for (const ExplainLink& e : c.explains) {
    data x;
    x.set("x", std::to_string(e.at.x));
    x.set("y", std::to_string(e.at.y));
    x.set("sample", std::to_string(e.at.sample));
    x.set("href", from_case_folder(e.file, folder));
    x.set("file", fs::path(e.file).filename().string());
    std::string error;
    std::string text = read_file(fs::path(report_dir) / e.file, error);
    x.set("text", error.empty() ? text : "The file " + error + ".");
    list << x;
  }
  d.set("explains", list);
  d.set("has_explains", !c.explains.empty());
}

data bad_page_data(const std::string& case_name, const std::vector<BadSample>& all, size_t page, size_t pages,
                   bool cpu_judged, const std::string& cpu_method) {
  data d;
  d.set("name", case_name);
  d.set("page", std::to_string(page));
  d.set("page_count", std::to_string(pages));
  d.set("total", std::to_string(all.size()));
  d.set("per_page", std::to_string(kBadSamplesPerPage));
  const size_t first = (page - 1) * kBadSamplesPerPage;
  const size_t last = std::min(all.size(), first + kBadSamplesPerPage);
  d.set("first", std::to_string(first + 1));
  d.set("last", std::to_string(last));
  d.set("judged_label", judged_label(cpu_method));
  d.set("reference_label", reference_label(cpu_method));
  d.set("first_href", optional_text(page > 1 ? bad_samples_page(1) : ""));
  d.set("prev_href", optional_text(page > 1 ? bad_samples_page(page - 1) : ""));
  d.set("next_href", optional_text(page < pages ? bad_samples_page(page + 1) : ""));
  d.set("last_href", optional_text(page < pages ? bad_samples_page(pages) : ""));
  data rows{data::type::list};
  for (size_t i = first; i < last; ++i) {
    data row = bad_sample_row(all[i], cpu_judged);
    row.set("n", std::to_string(i + 1));
    rows << row;
  }
  d.set("bad", rows);
  return d;
}

}  // namespace

std::string report_number(double v) { return fmt::format("{:.6g}", v); }

bool cpu_is_judged(std::string_view cpu_method) { return cpu_method != "exact"; }

SampleClass judged_class(SampleClass c, bool cpu_judged) {
  if (!cpu_judged) return c;
  if (c == SampleClass::Missing) return SampleClass::Unexpected;
  if (c == SampleClass::Unexpected) return SampleClass::Missing;
  return c;
}

std::string judged_kind(const std::string& kind, bool cpu_judged) {
  const bool missing = cpu_judged ? kind == "unexpected" : kind == "missing";
  const bool unexpected = cpu_judged ? kind == "missing" : kind == "unexpected";
  if (missing) return "judged lacks";
  if (unexpected) return "judged adds";
  return kind == "wrong_owner" ? "wrong owner" : kind;
}

std::string bad_samples_page(size_t n) { return fmt::format("bad-samples-{}.html", n); }

uint64_t bad_sample_count(const DiffSummary& diff) { return diff.coverage_mismatches() + diff.depth.mismatches; }

size_t bad_sample_pages(const DiffSummary& diff) {
  return size_t((bad_sample_count(diff) + kBadSamplesPerPage - 1) / kBadSamplesPerPage);
}

void write_bad_sample_pages(const std::string& report_dir, const std::string& case_name, const CaseResult& result) {
  if (!result.diff || !result.expected || !result.actual) return;
  const size_t pages = bad_sample_pages(result.diff->summary);
  if (pages == 0) return;
  const SceneDiff all =
      diff_results(*result.expected, *result.actual, result.diff->summary.profile, std::numeric_limits<size_t>::max());
  const bool cpu_judged = cpu_is_judged(result.cpu_method);
  const fs::path folder = fs::path(report_dir) / case_folder(case_name);
  for (size_t n = 1; n <= pages; ++n)
    write_text_file_atomic(
        (folder / bad_samples_page(n)).string(),
        render(bad_samples_template(),
               bad_page_data(case_name, all.summary.first_bad, n, pages, cpu_judged, result.cpu_method),
               "bad-samples"));
}

std::string render_case_html(const std::string& report_dir, const RunInfo& info, const CaseRecord& c) {
  const bool cpu_judged = cpu_is_judged(c.cpu_method);
  const std::string folder = case_folder(c.name);
  const StatusStyle& style = status_style(c.status);
  data d;
  d.set("name", c.name);
  d.set("profile", info.profile);
  d.set("device", info.device);
  d.set("status", c.status);
  d.set("key", std::string(style.key));
  d.set("background", std::string(style.background));
  d.set("colour", std::string(style.colour));
  d.set("status_meaning", std::string(style.meaning));
  d.set("verdict", to_string(c.verdict));
  d.set("expectation", c.expectation);
  d.set("message", c.message);
  d.set("reason", optional_text(c.expectation_reason));
  d.set("cpu_method", c.cpu_method);
  d.set("judged_label", judged_label(c.cpu_method));
  d.set("reference_label", reference_label(c.cpu_method));
  d.set("source", c.source);
  d.set("width", std::to_string(c.width));
  d.set("height", std::to_string(c.height));
  d.set("compared", c.diff.has_value());
  std::string note;
  if (c.diff && cpu_judged)
    note = fmt::format(
        "The message names samples as the diff does, from the CPU's side (missing: the CPU covers the sample, the "
        "device does not). Judged here is the CPU method: it adds {} sample(s) and lacks {}.",
        c.diff->missing, c.diff->unexpected);
  d.set("judged_note", optional_text(note));
  if (c.diff) {
    set_numbers(d, *c.diff, cpu_judged);
    set_bad_samples(d, c, folder, cpu_judged);
  }
  set_images(d, c, folder, cpu_judged);
  set_explains(d, c, report_dir, folder);
  std::string error;
  const std::string scene = read_file(c.source, error);
  d.set("scene_text", optional_text(scene));
  d.set("scene_error", optional_text(error.empty() ? (scene.empty() ? "The scene file is empty." : "")
                                                   : "The scene file " + c.source + " " + error + "."));
  return render(case_template(), d, "case");
}

}  // namespace rastercmp
