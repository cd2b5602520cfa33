#include "compare/run_outputs.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include "compare/expectations.hpp"
#include "model/errors.hpp"
#include "model/image_io.hpp"

namespace rastercmp {
namespace fs = std::filesystem;
namespace {

constexpr Verdict kVerdictOrder[] = {Verdict::Pass,         Verdict::Fail,          Verdict::QualityWarning,
                                     Verdict::NotSupported, Verdict::ResourceError, Verdict::InternalError,
                                     Verdict::Crash,        Verdict::Timeout};

std::string xml_escape(std::string_view text) {
  std::string out;
  for (char ch : text) {
    switch (ch) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default:
        // XML 1.0 allows no control characters but tab, newline and carriage return.
        if (static_cast<unsigned char>(ch) < 0x20 && ch != '\t' && ch != '\n' && ch != '\r')
          out += ' ';
        else
          out += ch;
    }
  }
  return out;
}

std::string junit_testcase(const CaseRecord& c) {
  const auto dot = c.name.rfind('.');
  const std::string classname = dot == std::string::npos ? "rastercmp" : c.name.substr(0, dot);
  const std::string leaf = dot == std::string::npos ? c.name : c.name.substr(dot + 1);
  std::string xml = fmt::format("    <testcase classname=\"{}\" name=\"{}\" time=\"{:.3f}\">\n", xml_escape(classname),
                                xml_escape(leaf), c.duration_s);
  const std::string detail = xml_escape(
      fmt::format("{} (verdict {}, expected {}): {}", c.status, to_string(c.verdict), c.expectation, c.message));
  if (c.fails_run) {
    const char* element = c.status == "Crash" ? "error" : "failure";
    xml += fmt::format("      <{0} type=\"{1}\" message=\"{2}\">{2}</{0}>\n", element, xml_escape(c.status), detail);
  } else if (c.status == "Skip") {
    xml += fmt::format("      <skipped message=\"{}\"/>\n", detail);
  } else if (c.status != "Pass") {
    xml += fmt::format("      <system-out>{}</system-out>\n", detail);
  }
  return xml + "    </testcase>\n";
}

RunInfo run_info_from_json(const nlohmann::json& j, const std::string& file) {
  RunInfo info;
  try {
    info.profile = j.at("profile").get<std::string>();
    info.profile_warning = j.value("profile_warning", std::string());
    info.device = j.at("device").get<std::string>();
    info.driver = j.at("driver").get<std::string>();
    info.fma = j.at("fma").get<bool>();
    info.complete = j.at("complete").get<bool>();
    info.interrupted = j.at("interrupted").get<bool>();
    info.not_run = j.at("not_run").get<std::vector<std::string>>();
    // Older summaries have no shard: a whole run, its size unknown (0).
    if (j.contains("shard")) {
      const std::string shard = j.at("shard").get<std::string>();
      const auto slash = shard.find('/');
      if (slash == std::string::npos) throw InputError(file, "$.shard", "expected I/N, found " + shard);
      info.shard_index = uint32_t(std::stoul(shard.substr(0, slash)));
      info.shard_count = uint32_t(std::stoul(shard.substr(slash + 1)));
      if (info.shard_count == 0 || info.shard_index >= info.shard_count)
        throw InputError(file, "$.shard", "expected I/N with I < N, found " + shard);
    }
    info.selected_cases = j.value("selected_cases", size_t(0));
    info.missing_unnamed = j.value("missing_unnamed", size_t(0));
  } catch (const std::logic_error& e) {  // std::stoul
    throw InputError(file, "$.shard", std::string("expected I/N: ") + e.what());
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file, "$", std::string("expected a rastercmp summary.json: ") + e.what());
  }
  return info;
}

}  // namespace

std::string results_csv_line(const CaseRecord& c) {
  return fmt::format("{},{},{:.3f}\n", c.name, c.status, c.duration_s);
}

std::string results_csv(const RunInfo& info, const std::vector<CaseRecord>& records) {
  std::string csv;
  for (const CaseRecord& c : records) csv += results_csv_line(c);
  for (const std::string& name : info.not_run) csv += fmt::format("{},Missing,0.000\n", name);
  return csv;
}

std::map<std::string, double> parse_results_csv(std::string_view text, const std::string& file) {
  std::map<std::string, double> durations;
  size_t line_number = 0;
  while (!text.empty()) {
    const auto end = text.find('\n');
    const std::string line(text.substr(0, end));
    text = end == std::string_view::npos ? std::string_view{} : text.substr(end + 1);
    ++line_number;
    if (line.empty()) continue;
    const auto last = line.rfind(',');
    const auto middle = last == std::string::npos || last == 0 ? std::string::npos : line.rfind(',', last - 1);
    if (middle == std::string::npos)
      throw InputError(file, fmt::format("line {}", line_number), "expected `name,status,duration`");
    try {
      durations[line.substr(0, middle)] = std::stod(line.substr(last + 1));
    } catch (const std::exception&) {
      throw InputError(file, fmt::format("line {}", line_number), "expected a duration in seconds");
    }
  }
  return durations;
}

std::string failures_csv(const RunInfo& info, const std::vector<CaseRecord>& records) {
  std::vector<std::pair<std::string, std::string>> failing;
  for (const CaseRecord& c : records)
    if (!is_success_status(c.status)) failing.emplace_back(c.name, c.status);
  for (const std::string& name : info.not_run) failing.emplace_back(name, "Missing");
  std::sort(failing.begin(), failing.end());
  std::string csv;
  for (const auto& [name, status] : failing) csv += fmt::format("{},{}\n", name, status);
  return csv;
}

std::string junit_xml(const RunInfo& info, const std::vector<CaseRecord>& records) {
  size_t failures = info.not_run.size(), errors = 0, skipped = 0;
  double total_s = 0;
  for (const CaseRecord& c : records) {
    total_s += c.duration_s;
    if (c.fails_run && c.status == "Crash")
      ++errors;
    else if (c.fails_run)
      ++failures;
    else if (c.status == "Skip")
      ++skipped;
  }
  const size_t tests = records.size() + info.not_run.size();
  std::string xml = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  xml += fmt::format("<testsuites name=\"rastercmp\" tests=\"{0}\" failures=\"{1}\" errors=\"{2}\" time=\"{3:.3f}\">\n",
                     tests, failures, errors, total_s);
  xml += fmt::format(
      "  <testsuite name=\"rastercmp\" tests=\"{0}\" failures=\"{1}\" errors=\"{2}\" skipped=\"{3}\" "
      "time=\"{4:.3f}\">\n",
      tests, failures, errors, skipped, total_s);
  for (const CaseRecord& c : records) xml += junit_testcase(c);
  for (const std::string& name : info.not_run) {
    CaseRecord missing;
    missing.name = name;
    missing.status = "Missing";
    missing.fails_run = true;
    missing.message = info.complete ? "no result" : "no result: the run did not reach this case (yet)";
    xml += junit_testcase(missing);
  }
  return xml + "  </testsuite>\n</testsuites>\n";
}

std::string summary_json(const RunInfo& info, const std::vector<CaseRecord>& records) {
  nlohmann::ordered_json j;
  j["profile"] = info.profile;
  if (!info.profile_warning.empty()) j["profile_warning"] = info.profile_warning;
  j["device"] = info.device;
  j["driver"] = info.driver;
  j["fma"] = info.fma;
  j["complete"] = info.complete;
  j["interrupted"] = info.interrupted;
  j["not_run"] = info.not_run;
  j["shard"] = fmt::format("{}/{}", info.shard_index, info.shard_count);
  j["selected_cases"] = info.selected_cases;
  if (info.missing_unnamed != 0) j["missing_unnamed"] = info.missing_unnamed;
  j["passed"] = run_passed(info, records);
  j["cases_run"] = records.size();
  nlohmann::ordered_json verdicts;
  for (Verdict v : kVerdictOrder)
    verdicts[to_string(v)] = std::count_if(records.begin(), records.end(), [&](auto& c) { return c.verdict == v; });
  j["verdicts"] = verdicts;
  auto statuses = count_statuses(records);
  if (!info.not_run.empty() || info.missing_unnamed != 0)
    statuses["Missing"] += info.not_run.size() + info.missing_unnamed;
  j["statuses"] = statuses;
  nlohmann::ordered_json cases = nlohmann::ordered_json::array();
  for (const CaseRecord& c : records) cases.push_back(case_to_json(c, true));
  j["cases"] = cases;
  return j.dump(2) + "\n";
}

ParsedSummary parse_summary_json(std::string_view text, const std::string& file) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file, "$", std::string("expected valid JSON: ") + e.what());
  }
  ParsedSummary parsed{run_info_from_json(j, file), {}};
  if (!j.contains("cases") || !j["cases"].is_array()) throw InputError(file, "$.cases", "expected an array");
  for (size_t i = 0; i < j["cases"].size(); ++i)
    parsed.records.push_back(case_from_json(j["cases"][i], file, fmt::format("$.cases[{}]", i)));
  return parsed;
}

void write_run_files(const std::string& out_dir, const RunInfo& info, const std::vector<CaseRecord>& records) {
  const fs::path out(out_dir);
  // Written together: a full disk leaves the earlier four, never a summary.json of one case fewer
  // than results.csv. summary.json, the verdict, is renamed last.
  write_text_files_together({{(out / "results.csv").string(), results_csv(info, records)},
                             {(out / "failures.csv").string(), failures_csv(info, records)},
                             {(out / "junit.xml").string(), junit_xml(info, records)},
                             {(out / "summary.json").string(), summary_json(info, records)}});
}

}  // namespace rastercmp
