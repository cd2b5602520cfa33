// The report page (compare/report.hpp): records → mustache data → HTML.
#include <fmt/core.h>

#include <filesystem>
#include <kainjow/mustache.hpp>
#include <stdexcept>

#include "compare/depth_units.hpp"
#include "compare/report.hpp"
#include "compare/report_template.hpp"
#include "model/image_io.hpp"

namespace rastercmp {
namespace {

using kainjow::mustache::data;
using kainjow::mustache::mustache;

std::string number(double v) { return fmt::format("{:.6g}", v); }

std::string owner_text(uint32_t owner) {
  if (owner == kOwnerBackground) return "background";
  return fmt::format("draw {} prim {}", owner_draw(owner), owner_primitive(owner));
}

// A section that is left out when the text is empty (a non-empty string opens it).
data optional_text(const std::string& text) { return text.empty() ? data(false) : data(text); }

data bad_sample_data(const BadSample& b, const std::vector<ExplainLink>& explains) {
  data d;
  d.set("x", std::to_string(b.at.x));
  d.set("y", std::to_string(b.at.y));
  d.set("sample", std::to_string(b.at.sample));
  d.set("kind", b.kind);
  d.set("expected_owner", owner_text(b.expected_owner));
  d.set("actual_owner", owner_text(b.actual_owner));
  d.set("expected_depth", b.has_depth ? fmt::format("{:#x}", b.expected_depth_raw) : "-");
  d.set("actual_depth", b.has_depth ? fmt::format("{:#x}", b.actual_depth_raw) : "-");
  d.set("depth_diff", b.depth_diff_raw ? fmt::format("{} ({} r)", b.depth_diff_raw, number(b.depth_diff_r)) : "-");
  std::string link;
  for (const ExplainLink& e : explains)
    if (e.at == b.at) link = e.file;
  d.set("explain", optional_text(link));
  return d;
}

void set_diff_data(data& d, const DiffSummary* s) {
  auto count = [&](const char* key, uint64_t v) { d.set(key, s ? std::to_string(v) : "-"); };
  count("missing", s ? s->missing : 0);
  count("unexpected", s ? s->unexpected : 0);
  count("wrong_owner", s ? s->wrong_owner : 0);
  count("allowed", s ? s->allowed : 0);
  count("depth_mismatches", s ? s->depth.mismatches : 0);
  count("max_depth", s ? s->depth.max_raw : 0);
  count("depth_p50", s ? s->depth.p50_raw : 0);
  count("depth_p95", s ? s->depth.p95_raw : 0);
  count("pixels", s ? s->pixels : 0);
  count("bad_pixels", s ? s->bad_pixels : 0);
  count("covered_match", s ? s->covered_match : 0);
  d.set("max_depth_r", s ? number(s->depth.max_r) : "-");
  d.set("depth_p50_r", s ? number(s->depth.p50_r) : "-");
  d.set("depth_p95_r", s ? number(s->depth.p95_r) : "-");
  d.set("compared", s != nullptr);
  if (!s) return;
  d.set("samples", std::to_string(s->samples));
  d.set("depth_format", to_string(s->depth_format));
  d.set("depth_unit", s->depth_compared ? depth_unit_name(s->depth_format) : "- (depth not compared)");
  d.set("max_depth_at",
        fmt::format("({}, {}) sample {}", s->depth.max_at.x, s->depth.max_at.y, s->depth.max_at.sample));
}

data case_data(const CaseRecord& c) {
  data d;
  d.set("name", c.name);
  d.set("anchor", "case-" + case_folder(c.name).substr(6));
  d.set("source", c.source);
  d.set("cpu_method", c.cpu_method);
  d.set("status", c.status);
  d.set("verdict", to_string(c.verdict));
  d.set("expectation", c.expectation);
  d.set("message", c.message);
  d.set("row_class", c.fails_run ? "fails" : "ok");
  d.set("width", std::to_string(c.width));
  d.set("height", std::to_string(c.height));
  set_diff_data(d, c.diff ? &*c.diff : nullptr);
  d.set("cpu_image", optional_text(c.images.cpu));
  d.set("vulkan_image", optional_text(c.images.vulkan));
  d.set("mask_image", optional_text(c.images.mask));
  d.set("depth_image", optional_text(c.images.depth_heatmap));
  data bad{data::type::list};
  if (c.diff)
    for (const BadSample& b : c.diff->first_bad) bad << bad_sample_data(b, c.explains);
  d.set("has_bad", c.diff && !c.diff->first_bad.empty());
  d.set("bad", bad);
  return d;
}

data page_data(const RunInfo& info, const std::vector<CaseRecord>& records) {
  data page;
  page.set("profile", info.profile);
  page.set("device", info.device);
  page.set("driver", info.driver);
  page.set("fma", info.fma ? "yes" : "no");
  page.set("interrupted", info.interrupted);
  page.set("not_run_count", std::to_string(info.not_run.size()));
  page.set("run_verdict", info.interrupted            ? "interrupted"
                          : !info.complete            ? "incomplete"
                          : run_passed(info, records) ? "pass"
                                                      : "fail");
  page.set("case_count", std::to_string(records.size()));
  data counts{data::type::list};
  const auto statuses = count_statuses(records);
  size_t i = 0;
  for (const auto& [status, n] : statuses) {
    data entry;
    entry.set("status", status);
    entry.set("count", std::to_string(n));
    entry.set("last", ++i == statuses.size());
    counts << entry;
  }
  page.set("counts", counts);
  data cases{data::type::list};
  for (const CaseRecord& c : records) cases << case_data(c);
  page.set("cases", cases);
  return page;
}

}  // namespace

std::string render_report_html(const RunInfo& info, const std::vector<CaseRecord>& records) {
  mustache page{std::string(report_template())};
  if (!page.is_valid()) throw std::runtime_error("the report template does not parse: " + page.error_message());
  std::string html = page.render(page_data(info, records));
  if (!page.is_valid()) throw std::runtime_error("the report template did not render: " + page.error_message());
  return html;
}

void write_report_html(const std::string& report_dir, const RunInfo& info, const std::vector<CaseRecord>& records) {
  ensure_output_dir(report_dir);
  write_text_file_atomic((std::filesystem::path(report_dir) / "index.html").string(),
                         render_report_html(info, records));
}

}  // namespace rastercmp
