// The HTML report: the case images carry the CTS mask colours (seen from the judged renderer)
// and the inferno heatmap (only where depth differs); the index lists failures first with the
// baseline's reasons; a case page shows its images, numbers, bad samples (all of them, paginated),
// explanations and scene; in headless Chromium every link and image resolves, nothing overflows
// 1280 px, no script fails, and screenshots of the index and a failing case are not blank.
#include <OpenImageIO/imageio.h>
#include <fmt/core.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>

#include "compare/case_judge.hpp"
#include "compare/case_run.hpp"
#include "compare/diff.hpp"
#include "compare/expectations.hpp"
#include "compare/report.hpp"
#include "compare/run_outputs.hpp"
#include "model/image_io.hpp"

namespace rastercmp {
namespace {
namespace fs = std::filesystem;

constexpr uint32_t kOwner = encode_owner(0, 1);

RenderResult square(uint32_t size) {
  RenderResult r;
  r.backend = "cpu";
  r.width = r.height = size;
  r.depth_format = DepthFormat::D16Unorm;
  r.owner.assign(size_t(size) * size, kOwnerBackground);
  r.depth_raw.assign(r.owner.size(), 0xFFFF);
  for (uint32_t y = 2; y < 6; ++y)
    for (uint32_t x = 2; x < 6; ++x) {
      r.owner[r.index(x, y)] = kOwner;
      r.depth_raw[r.index(x, y)] = 0x8000;
    }
  return r;
}

// Expected square; actual misses (2,2), adds (7,7), and is 8 LSB off at (3,3) and 2 LSB at (4,4).
CaseResult planted_case() {
  CaseResult c;
  c.expected = square(8);
  c.actual = square(8);
  c.actual->backend = "vulkan";
  c.actual->owner[c.actual->index(2, 2)] = kOwnerBackground;
  c.actual->owner[c.actual->index(7, 7)] = kOwner;
  c.actual->depth_raw[c.actual->index(3, 3)] += 8;
  c.actual->depth_raw[c.actual->index(4, 4)] += 2;
  c.diff = diff_results(*c.expected, *c.actual, CompareProfile::Lavapipe);
  c.verdict = decide_verdict(c.diff->summary, 0).verdict;
  c.message = decide_verdict(c.diff->summary, 0).message;
  return c;
}

std::vector<uint8_t> read_rgb(const fs::path& path, int& width, int& height) {
  auto in = OIIO::ImageInput::open(path.string());
  EXPECT_TRUE(in) << path;
  if (!in) return {};
  width = in->spec().width;
  height = in->spec().height;
  std::vector<uint8_t> rgb(size_t(width) * height * 3);
  EXPECT_EQ(in->spec().nchannels, 3);
  in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, rgb.data());
  return rgb;
}

Rgb pixel(const std::vector<uint8_t>& rgb, int width, int x, int y) {
  const size_t i = (size_t(y) * width + x) * 3;
  return {rgb[i], rgb[i + 1], rgb[i + 2]};
}

size_t count_matches(const std::string& text, const std::string& pattern) {
  const std::regex re(pattern);
  return size_t(std::distance(std::sregex_iterator(text.begin(), text.end(), re), std::sregex_iterator()));
}

// A fresh folder for one test, removed when the test ends (one per process: ctest runs tests in
// parallel processes).
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& name)
      : path_(fs::temp_directory_path() / ("rastercmp_test_report_html_" + std::to_string(getpid()) + "_" + name)) {
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

TEST(ReportImages, MaskUsesTheCtsColours) {
  const ScratchDir scratch_mask("mask");
  const fs::path& dir = scratch_mask.path();
  const CaseImages images = write_case_images(dir.string(), "rastercmp.test.planted", planted_case());
  EXPECT_EQ(images.mask, "cases/rastercmp.test.planted/mask.png");
  int w = 0, h = 0;
  const auto mask = read_rgb(dir / images.mask, w, h);
  ASSERT_EQ(w, 8);
  EXPECT_EQ(pixel(mask, w, 2, 2), kMaskMissing);
  EXPECT_EQ(pixel(mask, w, 7, 7), kMaskUnexpected);
  EXPECT_EQ(pixel(mask, w, 3, 3), kMaskCorrect);
  EXPECT_EQ(pixel(mask, w, 0, 0), kMaskBackground);
  EXPECT_TRUE(fs::exists(dir / images.cpu));
  EXPECT_TRUE(fs::exists(dir / images.vulkan));
}

// Under a classic CPU method the CPU is judged: a sample only the CPU covers is one it adds (red),
// a sample only the device covers is one it lacks (magenta).
TEST(ReportImages, MaskUnderACpuMethodJudgesTheCpu) {
  const ScratchDir scratch_mask("mask_method");
  CaseResult planted = planted_case();
  planted.cpu_method = "fill=float_edge";
  const CaseImages images = write_case_images(scratch_mask.path().string(), "rastercmp.test.method", planted);
  int w = 0, h = 0;
  const auto mask = read_rgb(scratch_mask.path() / images.mask, w, h);
  ASSERT_EQ(w, 8);
  EXPECT_EQ(pixel(mask, w, 2, 2), kMaskUnexpected);
  EXPECT_EQ(pixel(mask, w, 7, 7), kMaskMissing);
  EXPECT_EQ(judged_kind("missing", true), "judged adds");
  EXPECT_EQ(judged_kind("missing", false), "judged lacks");
  EXPECT_EQ(judged_kind("unexpected", true), "judged lacks");
  EXPECT_EQ(judged_kind("depth", true), "depth");
}

TEST(ReportImages, HeatmapIsInfernoNormalisedToTheLargestDifference) {
  const ScratchDir scratch_heat("heat");
  const fs::path& dir = scratch_heat.path();
  const CaseImages images = write_case_images(dir.string(), "rastercmp.test.planted", planted_case());
  int w = 0, h = 0;
  const auto heat = read_rgb(dir / images.depth_heatmap, w, h);
  ASSERT_EQ(w, 8);
  const Rgb none = pixel(heat, w, 0, 0), largest = pixel(heat, w, 3, 3), quarter = pixel(heat, w, 4, 4);
  EXPECT_LT(int(none[0]) + none[1] + none[2], 30) << "inferno(0) is near black";
  EXPECT_GT(int(largest[0]) + largest[1], 400) << "inferno(1) is pale yellow";
  EXPECT_LT(int(none[0]) + none[1] + none[2], int(quarter[0]) + quarter[1] + quarter[2]);
  EXPECT_LT(int(quarter[0]) + quarter[1] + quarter[2], int(largest[0]) + largest[1] + largest[2]);
  // The colour bar runs through the same map: black at 0, pale yellow at 1.
  const std::string bar = depth_colour_bar_css();
  EXPECT_EQ(bar.rfind("linear-gradient(to right, rgb(", 0), 0u) << bar;
  EXPECT_EQ(count_matches(bar, "rgb\\("), 11u) << bar;
  EXPECT_NE(bar.find(fmt::format("rgb({},{},{}) 0%", none[0], none[1], none[2])), std::string::npos) << bar;
  EXPECT_NE(bar.find(fmt::format("rgb({},{},{}) 100%", largest[0], largest[1], largest[2])), std::string::npos) << bar;
}

TEST(ReportImages, NoHeatmapWithoutADepthDifference) {
  CaseResult coverage_only = planted_case();
  coverage_only.actual->depth_raw = coverage_only.expected->depth_raw;
  coverage_only.diff = diff_results(*coverage_only.expected, *coverage_only.actual, CompareProfile::Lavapipe);
  ASSERT_TRUE(coverage_only.diff->summary.depth_compared);
  ASSERT_EQ(coverage_only.diff->summary.depth.mismatches, 0u);
  const ScratchDir scratch("no_heat");
  const CaseImages images = write_case_images(scratch.path().string(), "rastercmp.test.flat", coverage_only);
  EXPECT_EQ(images.depth_heatmap, "");
  EXPECT_FALSE(fs::exists(scratch.path() / case_folder("rastercmp.test.flat") / "depth.png"));
  EXPECT_FALSE(images.mask.empty());
}

TEST(ReportImages, NotSupportedCaseHasNoImages) {
  CaseResult unsupported;
  unsupported.verdict = Verdict::NotSupported;
  const ScratchDir scratch("none");
  EXPECT_EQ(write_case_images(scratch.path().string(), "x", unsupported), CaseImages{});
  EXPECT_FALSE(fs::exists(scratch.path() / "cases"));
}

TEST(ReportImages, CaseFoldersAreSafeNames) {
  EXPECT_EQ(case_folder("rastercmp.fill.top_left"), "cases/rastercmp.fill.top_left");
  EXPECT_EQ(case_folder("../a b/c"), "cases/.._a_b_c");
  EXPECT_EQ(case_folder(".."), "cases/_..");
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// 16x16, every pixel covered by the CPU and none by the device: 256 bad samples, two pages.
CaseResult all_missing_case() {
  CaseResult c;
  c.expected = square(16);
  c.expected->owner.assign(c.expected->owner.size(), kOwner);
  c.actual = square(16);
  c.actual->backend = "vulkan";
  c.actual->owner.assign(c.actual->owner.size(), kOwnerBackground);
  c.diff = diff_results(*c.expected, *c.actual, CompareProfile::Lavapipe);
  c.verdict = Verdict::Fail;
  c.message = "256 missing";
  return c;
}

TEST(ReportPages, EveryBadSampleIsListedPaginated) {
  const ScratchDir scratch("pages");
  const CaseResult result = all_missing_case();
  ASSERT_EQ(bad_sample_count(result.diff->summary), 256u);
  ASSERT_EQ(bad_sample_pages(result.diff->summary), 2u);
  write_case_images(scratch.path().string(), "rastercmp.t.all", result);
  const fs::path folder = scratch.path() / case_folder("rastercmp.t.all");
  const std::string first = read_file(folder / "bad-samples-1.html"), second = read_file(folder / "bad-samples-2.html");
  EXPECT_EQ(count_matches(first, "<tr><td>[0-9]+</td>"), kBadSamplesPerPage);
  EXPECT_EQ(count_matches(second, "<tr><td>[0-9]+</td>"), 56u);
  EXPECT_NE(second.find("bad samples 201&ndash;256 of 256"), std::string::npos);
  EXPECT_NE(second.find("<tr><td>256</td><td class=\"name\">15, 15, 0</td><td class=\"name\">judged lacks</td>"),
            std::string::npos);
  EXPECT_NE(first.find("href=\"bad-samples-2.html\">next"), std::string::npos);
  EXPECT_FALSE(fs::exists(folder / "bad-samples-3.html"));
}

// Cases of every group, out of order: a pass, a failure, an expected failure with its reason, an
// unsupported case, a quality warning, a crash, and a 256-sample failure judged under a method.
std::vector<CaseRecord> write_report(const fs::path& report, const fs::path& scenes) {
  const CaseResult planted = planted_case();
  CaseResult same = planted;
  same.actual = same.expected;
  same.diff = diff_results(*same.expected, *same.actual, CompareProfile::Lavapipe);
  same.verdict = Verdict::Pass;
  same.message = "0 differences";
  CaseResult unsupported;
  unsupported.verdict = Verdict::NotSupported;
  unsupported.message = "cpu profile: polygon_mode line";
  CaseResult warning = same;
  warning.verdict = Verdict::QualityWarning;
  CaseResult crash;
  crash.verdict = Verdict::InternalError;
  crash.message = "the process died";
  CaseResult method = all_missing_case();
  method.cpu_method = "fill=float_edge";
  Expectations expectations;
  expectations.baseline["rastercmp.t.expected"] = "Fail";
  expectations.reasons["rastercmp.t.expected"] = "no tie rule: <both> sides fill";
  std::vector<CaseRecord> records;
  fs::create_directories(scenes);
  for (const auto& [name, result] :
       {std::pair{"rastercmp.t.a_pass", same}, std::pair{"rastercmp.t.crash", crash},
        std::pair{"rastercmp.t.expected", planted}, std::pair{"rastercmp.t.fail", planted},
        std::pair{"rastercmp.t.method", method}, std::pair{"rastercmp.t.unsupported", unsupported},
        std::pair{"rastercmp.t.warn", warning}}) {
    const std::string source = (scenes / (std::string(name) + ".json")).string();
    write_text_file_atomic(source, fmt::format("{{\"name\": \"{}\", \"note\": \"<b>&</b>\"}}\n", name));
    const SuiteCase suite_case{name, source, Scene{}};
    CaseRecord r = make_case_record(suite_case, result, expectations);
    r.images = write_case_images(report.string(), name, result);
    records.push_back(r);
  }
  records[1].status = "Crash";  // as the runner names a case whose process died
  records[3].explains.push_back({{2, 2, 0}, "cases/rastercmp.t.fail/explain_2_2_s0.txt"});
  write_text_file_atomic((report / records[3].explains[0].file).string(), "rastercmp.t.fail: pixel (2, 2) <history>\n");
  write_report_html(report.string(), RunInfo{"lavapipe", "llvmpipe <test>", "Mesa", true, true, false, {}, ""}, records);
  return records;
}

std::vector<std::string> row_statuses(const std::string& html) {
  std::vector<std::string> statuses;
  const std::regex row("<tr data-status=\"([^\"]*)\">");
  for (auto it = std::sregex_iterator(html.begin(), html.end(), row); it != std::sregex_iterator(); ++it)
    statuses.push_back((*it)[1]);
  return statuses;
}

TEST(ReportHtml, FailuresComeFirstAndEveryStatusHasItsOwnColour) {
  const ScratchDir scratch_page("order");
  const auto records = write_report(scratch_page.path() / "report", scratch_page.path() / "scenes");
  const std::string html = read_file(scratch_page.path() / "report" / "index.html");
  EXPECT_EQ(row_statuses(html), (std::vector<std::string>{"Crash", "Fail", "Fail", "Warn", "ExpectedFail", "Pass",
                                                          "Skip"}));
  std::vector<std::string> names;
  for (const CaseRecord* c : triage_order(records)) names.push_back(c->name);
  EXPECT_EQ(names,
            (std::vector<std::string>{"rastercmp.t.crash", "rastercmp.t.fail", "rastercmp.t.method", "rastercmp.t.warn",
                                      "rastercmp.t.expected", "rastercmp.t.a_pass", "rastercmp.t.unsupported"}));
  std::set<std::string_view> backgrounds, keys;
  for (const StatusStyle& s : status_styles()) {
    backgrounds.insert(s.background);
    keys.insert(s.key);
    EXPECT_NE(html.find(fmt::format(".st-{} {{ background: {};", s.key, s.background)), std::string::npos) << s.key;
  }
  EXPECT_EQ(backgrounds.size(), status_styles().size()) << "two statuses share a colour";
  EXPECT_EQ(keys.size(), status_styles().size());
  for (const char* status : {"Pass", "ExpectedFail", "Warn", "Fail", "Crash", "Timeout", "Flake", "Skip", "KnownFlake",
                             "Missing"})
    EXPECT_EQ(status_style(status).key, status);
  EXPECT_EQ(status_style("UnexpectedImprovement(Pass)").key, "UnexpectedImprovement");
  EXPECT_EQ(status_style("SomethingNew").key, "Other");
}

TEST(ReportHtml, IsDeterministicAndEscapesText) {
  const ScratchDir scratch_page("page");
  const fs::path report = scratch_page.path() / "report";
  const auto records = write_report(report, scratch_page.path() / "scenes");
  const RunInfo info{"lavapipe", "llvmpipe <test>", "Mesa", true, true, false, {}, ""};
  const std::string html = render_report_html(info, records);
  EXPECT_EQ(html, render_report_html(info, records));
  EXPECT_EQ(html, read_file(report / "index.html"));
  EXPECT_NE(html.find("llvmpipe &lt;test&gt;"), std::string::npos);
  EXPECT_EQ(html.find("llvmpipe <test>"), std::string::npos);
  EXPECT_EQ(html.find("http"), std::string::npos) << "no external resources";
  // The baseline's reason beside the expected failure, escaped.
  EXPECT_NE(html.find("<td class=\"note\">no tie rule: &lt;both&gt; sides fill</td>"), std::string::npos);
  EXPECT_NE(html.find("<a href=\"cases/rastercmp.t.fail/index.html\">rastercmp.<wbr>t.<wbr>fail<wbr></a>"),
            std::string::npos);
  // The judged renderer of each case.
  EXPECT_EQ(count_matches(html, "<td class=\"judged\">CPU fill=float_edge</td>"), 1u);
  EXPECT_EQ(count_matches(html, "<td class=\"judged\">Vulkan</td>"), 6u);
  EXPECT_EQ(render_case_html(report.string(), info, records[3]),
            read_file(report / case_folder("rastercmp.t.fail") / "index.html"));
}

TEST(ReportHtml, CasePageShowsTheCaseForTriage) {
  const ScratchDir scratch_page("case");
  const fs::path report = scratch_page.path() / "report";
  write_report(report, scratch_page.path() / "scenes");
  const std::string fail = read_file(report / case_folder("rastercmp.t.fail") / "index.html");
  EXPECT_NE(fail.find("Judged: <b>Vulkan device</b>; reference: <b>CPU model (exact)</b>"), std::string::npos);
  EXPECT_NE(fail.find("<img src=\"cpu.png\" alt=\"reference owners"), std::string::npos);
  EXPECT_NE(fail.find("<img src=\"vulkan.png\" alt=\"judged owners"), std::string::npos);
  EXPECT_NE(fail.find("<img src=\"mask.png\""), std::string::npos);
  EXPECT_NE(fail.find("<img src=\"depth.png\""), std::string::npos);
  EXPECT_NE(fail.find("class=\"colour-bar\" style=\"background: linear-gradient"), std::string::npos);
  EXPECT_NE(fail.find("<th class=\"name\">judged lacks</th><td>1</td><th class=\"name\">judged adds</th><td>1</td>"),
            std::string::npos);
  EXPECT_NE(fail.find("4 bad sample(s)"), std::string::npos);
  EXPECT_NE(fail.find("<a href=\"explain_2_2_s0.txt\">text</a>"), std::string::npos);
  EXPECT_NE(fail.find("<pre>rastercmp.t.fail: pixel (2, 2) &lt;history&gt;\n</pre>"), std::string::npos);
  EXPECT_NE(fail.find("&quot;note&quot;: &quot;&lt;b&gt;&amp;&lt;/b&gt;&quot;"), std::string::npos) << "scene source";
  // Under a method the CPU is judged: the 256 samples only the CPU covers are samples it adds.
  const std::string method = read_file(report / case_folder("rastercmp.t.method") / "index.html");
  EXPECT_NE(method.find("Judged: <b>CPU method fill=float_edge</b>; reference: <b>Vulkan device</b>"),
            std::string::npos);
  EXPECT_NE(method.find("<img src=\"vulkan.png\" alt=\"reference owners"), std::string::npos);
  EXPECT_NE(
      method.find("<th class=\"name\">judged lacks</th><td>0</td><th class=\"name\">judged adds</th><td>256</td>"),
      std::string::npos);
  EXPECT_NE(method.find("it adds 256 sample(s) and lacks 0."), std::string::npos);
  EXPECT_EQ(fail.find("it adds"), std::string::npos);
  EXPECT_NE(method.find("256 bad sample(s) in scan order (y, x, sample); the first 16 below"), std::string::npos);
  EXPECT_NE(method.find("<a href=\"bad-samples-2.html\">page 2</a>"), std::string::npos);
  EXPECT_NE(method.find("Depth identical"), std::string::npos);
  EXPECT_EQ(method.find("depth.png"), std::string::npos);
  const std::string expected = read_file(report / case_folder("rastercmp.t.expected") / "index.html");
  EXPECT_NE(expected.find("Baseline reason: no tie rule: &lt;both&gt; sides fill"), std::string::npos);
  const std::string crash = read_file(report / case_folder("rastercmp.t.crash") / "index.html");
  EXPECT_NE(crash.find("the process died"), std::string::npos);
  EXPECT_NE(crash.find("No images"), std::string::npos);
}

TEST(ReportHtml, CpuMethodLabelNamesTheOverridesInOrder) {
  CpuOptions options;
  EXPECT_EQ(cpu_method_label(options), "exact");
  options.methods = {{"fill", "scanline"}, {"depth", "bilinear"}};
  EXPECT_EQ(cpu_method_label(options), "fill=scanline depth=bilinear");
  EXPECT_FALSE(cpu_is_judged("exact"));
  EXPECT_TRUE(cpu_is_judged("fill=scanline depth=bilinear"));
}

std::string run_and_capture(const std::string& command) {
  std::string output;
  if (FILE* pipe = popen(command.c_str(), "r")) {
    char buffer[4096];
    size_t n = 0;
    while ((n = fread(buffer, 1, sizeof buffer, pipe)) > 0) output.append(buffer, n);
    pclose(pipe);
  }
  return output;
}

// Headless Chromium at 1280x900 on `page` with `mode` (--dump-dom, or --screenshot=FILE); stdout back.
std::string chromium(const fs::path& root, const fs::path& page, const std::string& mode) {
  const fs::path log = root / "chromium.log";
  const std::string command = fmt::format(
      "timeout 120 /usr/bin/chromium --headless --no-sandbox --disable-gpu --disable-background-networking "
      "--disable-component-update --disable-sync --no-first-run --user-data-dir={} --enable-logging=stderr --v=0 "
      "--window-size=1280,900 --hide-scrollbars {} file://{} 2>{}",
      (root / "profile").string(), mode, page.string(), log.string());
  return run_and_capture(command);
}

// Every href and src of a dumped DOM names an existing file (relative to the page's folder).
void expect_links_resolve(const std::string& dom, const fs::path& page) {
  const std::regex link("(href|src)=\"([^\"]*)\"");
  size_t links = 0;
  for (auto it = std::sregex_iterator(dom.begin(), dom.end(), link); it != std::sregex_iterator(); ++it) {
    const std::string target = (*it)[2];
    EXPECT_FALSE(target.empty()) << page;
    EXPECT_EQ(target.find(':'), std::string::npos) << "only relative links: " << target;
    EXPECT_TRUE(fs::is_regular_file(page.parent_path() / target)) << page << " links " << target;
    ++links;
  }
  EXPECT_GE(links, 2u) << page;  // at least the style sheet and a way back
}

// The dumped DOM of a page the report's script measured: no script error, no horizontal overflow.
void expect_fits(const std::string& dom, const fs::path& page) {
  std::smatch width;
  ASSERT_TRUE(std::regex_search(dom, width, std::regex("data-page-width=\"([0-9]+)\""))) << page;
  EXPECT_LE(std::stoi(width[1]), 1280) << page << " is wider than the window";
}

// A screenshot that is not blank: a 1280x900 PNG with many colours.
void expect_screenshot(const fs::path& png) {
  int w = 0, h = 0;
  const auto rgb = read_rgb(png, w, h);
  EXPECT_EQ(w, 1280);
  EXPECT_EQ(h, 900);
  std::set<uint32_t> colours;
  for (size_t i = 0; i + 2 < rgb.size(); i += 3)
    colours.insert(uint32_t(rgb[i]) << 16 | uint32_t(rgb[i + 1]) << 8 | rgb[i + 2]);
  EXPECT_GT(colours.size(), 8u) << png << " is nearly one colour";
}

TEST(ReportHtml, OpensInHeadlessChromiumWithWorkingLinksAndNoOverflow) {
  ASSERT_TRUE(fs::exists("/usr/bin/chromium")) << "chromium is missing (scripts/setup.sh installs it)";
  const ScratchDir scratch_chromium("chromium");
  const fs::path& root = scratch_chromium.path();
  const fs::path report = root / "report";
  write_report(report, root / "scenes");
  const fs::path index = report / "index.html", failing = report / case_folder("rastercmp.t.method") / "index.html";
  const std::string dom = chromium(root, index, "--dump-dom");
  ASSERT_NE(dom.find("</html>"), std::string::npos) << "no DOM dumped; chromium log:\n"
                                                    << read_file(root / "chromium.log");
  EXPECT_EQ(count_matches(dom, "<tr data-status="), 7u);
  EXPECT_NE(dom.find("data-script-ready=\"yes\""), std::string::npos) << "the inline script did not finish";
  EXPECT_NE(dom.find("<pre id=\"js-errors\"></pre>"), std::string::npos) << "a script error was written into the page";
  EXPECT_EQ(read_file(root / "chromium.log").find("CONSOLE"), std::string::npos) << read_file(root / "chromium.log");
  expect_links_resolve(dom, index);
  expect_fits(dom, index);
  // Every case page and bad-sample page: its links and images resolve.
  for (const auto& entry : fs::recursive_directory_iterator(report / "cases"))
    if (entry.path().extension() == ".html") expect_links_resolve(read_file(entry.path()), entry.path());
  const std::string case_dom = chromium(root, failing, "--dump-dom");
  EXPECT_EQ(count_matches(case_dom, "<img "), 3u);  // reference, judged, difference; depth identical
  expect_links_resolve(case_dom, failing);
  expect_fits(case_dom, failing);

  chromium(root, index, "--screenshot=" + (root / "index.png").string());
  chromium(root, report / case_folder("rastercmp.t.fail") / "index.html",
           "--screenshot=" + (root / "case.png").string());
  expect_screenshot(root / "index.png");
  expect_screenshot(root / "case.png");
}

}  // namespace
}  // namespace rastercmp
