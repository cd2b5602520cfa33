// The report's index page and the status table (compare/report.hpp): records → mustache data → HTML.
#include <fmt/core.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <kainjow/mustache.hpp>
#include <map>
#include <mutex>
#include <sstream>
#include <stdexcept>

#include "compare/report.hpp"
#include "compare/report_template.hpp"
#include "model/image_io.hpp"

namespace rastercmp {
namespace {

using kainjow::mustache::data;
using kainjow::mustache::mustache;

// One row per runner status (compare/expectations.hpp, deqp-runner's names; a verdict's status is
// runner_status(): NotSupported is Skip, QualityWarning Warn, ResourceError and InternalError Fail). Colours: failures
// in reds and browns, warnings yellow, expected failures blue, flakes lavender, passes green,
// cases not run on this device grey.
constexpr StatusStyle kStatusStyles[] = {
    {"Fail", 0, "#cc0000", "#ffffff",
     "the judged renderer differs where it must not, and the baseline does not expect it"},
    {"Crash", 0, "#5b0f00", "#ffffff", "the case's process died before it reported a result"},
    {"Timeout", 0, "#b45f06", "#ffffff", "the case ran past its time limit"},
    {"Missing", 0, "#434343", "#ffffff", "the case left no result"},
    {"UnexpectedImprovement", 0, "#ff9900", "#000000",
     "the baseline expects a failure, the case passed: update the baseline"},
    {"Warn", 1, "#ffd966", "#000000",
     "a QualityWarning (spec profile: what the specification leaves to quality); does not fail the run"},
    {"ExpectedFail", 2, "#9fc5e8", "#000000", "fails as the baseline expects (its reason beside it)"},
    {"KnownFlake", 2, "#b4a7d6", "#000000", "differs from its expectation, and its name matches a flake pattern"},
    {"Flake", 2, "#d9d2e9", "#000000", "failed, then passed when run again"},
    {"Pass", 3, "#93c47d", "#000000", "the judged renderer matches the reference"},
    {"Skip", 4, "#d9d9d9", "#000000",
     "not run: the CPU profile or the device does not support the scene, or a skips pattern left it out"},
    {"Other", 3, "#ffffff", "#000000", "a status this report has no colour for"},
};

data styles_data() {
  data list{data::type::list};
  for (const StatusStyle& s : kStatusStyles) {
    data d;
    d.set("key", std::string(s.key));
    d.set("label", std::string(s.key));
    d.set("background", std::string(s.background));
    d.set("colour", std::string(s.colour));
    d.set("meaning", std::string(s.meaning));
    list << d;
  }
  return list;
}

// The case name in pieces that end after each '.', so a long name wraps there (<wbr>).
data name_parts(const std::string& name) {
  data parts{data::type::list};
  size_t start = 0;
  while (start < name.size()) {
    const size_t dot = name.find('.', start);
    const size_t end = dot == std::string::npos ? name.size() : dot + 1;
    data part;
    part.set("part", name.substr(start, end - start));
    parts << part;
    start = end;
  }
  return parts;
}

data case_row(const CaseRecord& c) {
  const bool cpu_judged = cpu_is_judged(c.cpu_method);
  const DiffSummary* s = c.diff ? &*c.diff : nullptr;
  data d;
  d.set("name_parts", name_parts(c.name));
  d.set("href", case_folder(c.name) + "/index.html");
  d.set("status", c.status);
  d.set("key", std::string(status_style(c.status).key));
  d.set("reason", c.expectation_reason);
  d.set("judged", cpu_judged ? "CPU " + c.cpu_method : "Vulkan");
  auto count = [&](const char* key, uint64_t v) { d.set(key, s ? std::to_string(v) : "-"); };
  count("lacks", s ? (cpu_judged ? s->unexpected : s->missing) : 0);
  count("adds", s ? (cpu_judged ? s->missing : s->unexpected) : 0);
  count("wrong_owner", s ? s->wrong_owner : 0);
  count("allowed", s ? s->allowed : 0);
  count("depth_mismatches", s ? s->depth.mismatches : 0);
  d.set("max_depth_r", s ? report_number(s->depth.max_r) : "-");
  return d;
}

data page_data(const RunInfo& info, const std::vector<CaseRecord>& records) {
  data page;
  page.set("profile", info.profile);
  page.set("profile_warning", info.profile_warning);
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
  page.set("styles", styles_data());
  data counts{data::type::list};
  const auto statuses = count_statuses(records);
  size_t i = 0;
  for (const auto& [status, n] : statuses) {
    data entry;
    entry.set("status", status);
    entry.set("key", std::string(status_style(status).key));
    entry.set("count", std::to_string(n));
    entry.set("last", ++i == statuses.size());
    counts << entry;
  }
  page.set("counts", counts);
  data cases{data::type::list};
  for (const CaseRecord* c : triage_order(records)) cases << case_row(*c);
  page.set("cases", cases);
  return page;
}

// Rewrites a file only when its bytes change: the case pages are written again after every case.
void write_if_changed(const std::filesystem::path& path, const std::string& text) {
  std::ifstream in(path, std::ios::binary);
  if (in) {
    std::ostringstream old;
    old << in.rdbuf();
    if (old.str() == text) return;
  }
  write_text_file_atomic(path.string(), text);
}

// The inputs each case page was last written from, by its path, in this process: a run rewrites
// the report after every case, and only the pages whose record changed (the new case's) are
// rendered again. The scene and explanation files a page also reads do not change during a run.
class WrittenPages {
 public:
  static std::string inputs(const RunInfo& info, const CaseRecord& record) {
    return info.profile + '\n' + info.device + '\n' + case_to_json(record, true).dump();
  }
  bool current(const std::filesystem::path& page, const std::string& inputs) {
    const std::lock_guard<std::mutex> lock(mutex_);
    const auto it = written_.find(page.string());
    std::error_code ec;
    return it != written_.end() && it->second == inputs && std::filesystem::is_regular_file(page, ec);
  }
  void remember(const std::filesystem::path& page, const std::string& inputs) {
    const std::lock_guard<std::mutex> lock(mutex_);
    written_[page.string()] = inputs;
  }

 private:
  std::mutex mutex_;
  std::map<std::string, std::string> written_;
};

WrittenPages& written_pages() {
  static WrittenPages pages;
  return pages;
}

}  // namespace

std::span<const StatusStyle> status_styles() { return kStatusStyles; }

const StatusStyle& status_style(std::string_view status) {
  const std::string_view key = status.substr(0, status.find('('));
  for (const StatusStyle& s : kStatusStyles)
    if (s.key == key) return s;
  return kStatusStyles[std::size(kStatusStyles) - 1];
}

int status_group(const CaseRecord& record) { return record.fails_run ? 0 : status_style(record.status).group; }

std::vector<const CaseRecord*> triage_order(const std::vector<CaseRecord>& records) {
  std::vector<const CaseRecord*> order;
  for (const CaseRecord& c : records) order.push_back(&c);
  std::stable_sort(order.begin(), order.end(), [](const CaseRecord* a, const CaseRecord* b) {
    const int ga = status_group(*a), gb = status_group(*b);
    return ga != gb ? ga < gb : a->name < b->name;
  });
  return order;
}

std::string render_report_html(const RunInfo& info, const std::vector<CaseRecord>& records) {
  mustache page{std::string(report_template())};
  if (!page.is_valid()) throw std::runtime_error("the report template does not parse: " + page.error_message());
  std::string html = page.render(page_data(info, records));
  if (!page.is_valid()) throw std::runtime_error("the report template did not render: " + page.error_message());
  return html;
}

void write_report_html(const std::string& report_dir, const RunInfo& info, const std::vector<CaseRecord>& records) {
  namespace fs = std::filesystem;
  ensure_output_dir(report_dir);
  write_if_changed(fs::path(report_dir) / "style.css", std::string(report_css()));
  for (const CaseRecord& c : records) {
    const fs::path page = fs::path(report_dir) / case_folder(c.name) / "index.html";
    const std::string inputs = WrittenPages::inputs(info, c);
    if (written_pages().current(page, inputs)) continue;
    ensure_output_dir(page.parent_path().string());
    write_if_changed(page, render_case_html(report_dir, info, c));
    written_pages().remember(page, inputs);
  }
  write_text_file_atomic((fs::path(report_dir) / "index.html").string(), render_report_html(info, records));
}

}  // namespace rastercmp
