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
                                     Verdict::NotSupported, Verdict::ResourceError, Verdict::InternalError};

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
  const std::string detail = xml_escape(fmt::format("{} (verdict {}, expected {}): {}", c.status, to_string(c.verdict),
                                                    to_string(c.expectation), c.message));
  if (c.fails_run) {
    const char* element = c.verdict == Verdict::Fail || !is_failure(c.verdict) ? "failure" : "error";
    xml += fmt::format("      <{0} type=\"{1}\" message=\"{2}\">{2}</{0}>\n", element, xml_escape(c.status), detail);
  } else if (c.verdict == Verdict::NotSupported) {
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
    info.device = j.at("device").get<std::string>();
    info.driver = j.at("driver").get<std::string>();
    info.fma = j.at("fma").get<bool>();
    info.interrupted = j.at("interrupted").get<bool>();
    info.not_run = j.at("not_run").get<std::vector<std::string>>();
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file, "$", std::string("expected a rastercmp summary.json: ") + e.what());
  }
  return info;
}

}  // namespace

ResultsCsvWriter::ResultsCsvWriter(const std::string& path) : path_(path), file_(std::fopen(path.c_str(), "wb")) {
  if (file_ == nullptr) throw InputError(path, "", std::string("expected a writable file: ") + std::strerror(errno));
}

ResultsCsvWriter::~ResultsCsvWriter() {
  if (file_ != nullptr) std::fclose(file_);
}

void ResultsCsvWriter::append(const CaseRecord& record) {
  const std::string line = results_csv_line(record);
  if (std::fputs(line.c_str(), file_) < 0 || std::fflush(file_) != 0)
    throw InputError(path_, "", "could not append to the file");
}

std::string results_csv_line(const CaseRecord& c) {
  return fmt::format("{},{},{:.3f}\n", c.name, c.status, c.duration_s);
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

std::string failures_csv(const std::vector<CaseRecord>& records) {
  std::vector<const CaseRecord*> failing;
  for (const CaseRecord& c : records)
    if (is_failure(c.verdict) && c.status != "KnownFlake") failing.push_back(&c);
  std::sort(failing.begin(), failing.end(), [](auto* a, auto* b) { return a->name < b->name; });
  std::string csv;
  for (const CaseRecord* c : failing) csv += fmt::format("{},{}\n", c->name, to_string(c->verdict));
  return csv;
}

std::string junit_xml(const std::vector<CaseRecord>& records) {
  size_t failures = 0, errors = 0, skipped = 0;
  double total_s = 0;
  for (const CaseRecord& c : records) {
    total_s += c.duration_s;
    if (c.fails_run && (c.verdict == Verdict::Fail || !is_failure(c.verdict)))
      ++failures;
    else if (c.fails_run)
      ++errors;
    else if (c.verdict == Verdict::NotSupported)
      ++skipped;
  }
  std::string xml = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  xml += fmt::format("<testsuites name=\"rastercmp\" tests=\"{0}\" failures=\"{1}\" errors=\"{2}\" time=\"{3:.3f}\">\n",
                     records.size(), failures, errors, total_s);
  xml += fmt::format(
      "  <testsuite name=\"rastercmp\" tests=\"{0}\" failures=\"{1}\" errors=\"{2}\" skipped=\"{3}\" "
      "time=\"{4:.3f}\">\n",
      records.size(), failures, errors, skipped, total_s);
  for (const CaseRecord& c : records) xml += junit_testcase(c);
  return xml + "  </testsuite>\n</testsuites>\n";
}

std::string summary_json(const RunInfo& info, const std::vector<CaseRecord>& records) {
  nlohmann::ordered_json j;
  j["profile"] = info.profile;
  j["device"] = info.device;
  j["driver"] = info.driver;
  j["fma"] = info.fma;
  j["interrupted"] = info.interrupted;
  j["not_run"] = info.not_run;
  j["passed"] = run_passed(info, records);
  j["cases_run"] = records.size();
  nlohmann::ordered_json verdicts;
  for (Verdict v : kVerdictOrder)
    verdicts[to_string(v)] = std::count_if(records.begin(), records.end(), [&](auto& c) { return c.verdict == v; });
  j["verdicts"] = verdicts;
  j["statuses"] = count_statuses(records);
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
  write_text_file_atomic((out / "failures.csv").string(), failures_csv(records));
  write_text_file_atomic((out / "junit.xml").string(), junit_xml(records));
  write_text_file_atomic((out / "summary.json").string(), summary_json(info, records));
}

}  // namespace rastercmp
