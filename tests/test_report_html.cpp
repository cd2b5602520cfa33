// The HTML report: the case images carry the CTS mask colours and the inferno heatmap, and the
// page opens in headless Chromium with its table rows, its <img> tags and no script errors.
#include <OpenImageIO/imageio.h>
#include <fmt/core.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <regex>

#include "compare/case_judge.hpp"
#include "compare/case_run.hpp"
#include "compare/diff.hpp"
#include "compare/expectations.hpp"
#include "compare/report.hpp"
#include "compare/run_outputs.hpp"

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
}

TEST(ReportImages, NotSupportedCaseHasNoImages) {
  CaseResult unsupported;
  unsupported.verdict = Verdict::NotSupported;
  const ScratchDir scratch("none");
  EXPECT_EQ(write_case_images(scratch.path().string(), "x", unsupported), CaseImages{});
}

TEST(ReportImages, CaseFoldersAreSafeNames) {
  EXPECT_EQ(case_folder("rastercmp.fill.top_left"), "cases/rastercmp.fill.top_left");
  EXPECT_EQ(case_folder("../a b/c"), "cases/.._a_b_c");
  EXPECT_EQ(case_folder(".."), "cases/_..");
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

size_t count_matches(const std::string& text, const std::string& pattern) {
  const std::regex re(pattern);
  return size_t(std::distance(std::sregex_iterator(text.begin(), text.end(), re), std::sregex_iterator()));
}

// Three cases: a failing one with images, a passing one with images, an unsupported one.
std::vector<CaseRecord> write_report(const fs::path& report) {
  const CaseResult planted = planted_case();
  CaseResult same = planted;
  same.actual = same.expected;
  same.diff = diff_results(*same.expected, *same.actual, CompareProfile::Lavapipe);
  same.verdict = Verdict::Pass;
  CaseResult unsupported;
  unsupported.verdict = Verdict::NotSupported;
  unsupported.message = "cpu profile: polygon_mode line";
  std::vector<CaseRecord> records;
  const Expectations none;
  for (const auto& [name, result] : {std::pair{"rastercmp.t.fail", planted}, std::pair{"rastercmp.t.pass", same},
                                     std::pair{"rastercmp.t.unsupported", unsupported}}) {
    const SuiteCase suite_case{name, std::string(name) + ".json", Scene{}};
    CaseRecord r = make_case_record(suite_case, result, none);
    r.images = write_case_images(report.string(), name, result);
    records.push_back(r);
  }
  records[0].explains.push_back({{2, 2, 0}, "cases/rastercmp.t.fail/explain_2_2_s0.txt"});
  records[1].cpu_method = "fill=even_odd";
  write_report_html(report.string(), RunInfo{"lavapipe", "llvmpipe <test>", "Mesa", true, true, false, {}}, records);
  return records;
}

TEST(ReportHtml, IsDeterministicAndEscapesText) {
  const ScratchDir scratch_page("page");
  const fs::path& report = scratch_page.path();
  const auto records = write_report(report);
  const RunInfo info{"lavapipe", "llvmpipe <test>", "Mesa", true, true, false, {}};
  const std::string html = render_report_html(info, records);
  EXPECT_EQ(html, render_report_html(info, records));
  EXPECT_NE(html.find("llvmpipe &lt;test&gt;"), std::string::npos);
  EXPECT_EQ(html.find("llvmpipe <test>"), std::string::npos);
  EXPECT_NE(html.find("href=\"cases/rastercmp.t.fail/explain_2_2_s0.txt\""), std::string::npos);
  // The CPU method of each case, in its summary row and its section.
  EXPECT_EQ(count_matches(html, "<td class=\"name\">fill=even_odd</td>"), 1u);
  EXPECT_EQ(count_matches(html, "CPU method: <b>fill=even_odd</b>"), 1u);
  EXPECT_EQ(count_matches(html, "CPU method: <b>exact</b>"), 2u);
  EXPECT_EQ(html.find("http"), std::string::npos) << "no external resources";
}

TEST(ReportHtml, CpuMethodLabelNamesTheOverridesInOrder) {
  CpuOptions options;
  EXPECT_EQ(cpu_method_label(options), "exact");
  options.methods = {{"fill", "scanline"}, {"depth", "bilinear"}};
  EXPECT_EQ(cpu_method_label(options), "fill=scanline depth=bilinear");
}

TEST(ReportHtml, OpensInHeadlessChromiumWithRowsImagesAndNoErrors) {
  ASSERT_TRUE(fs::exists("/usr/bin/chromium")) << "chromium is missing: run scripts/setup.sh";
  const ScratchDir scratch_chromium("chromium");
  const fs::path& root = scratch_chromium.path();
  const fs::path report = root / "report";
  write_report(report);
  const fs::path log = root / "chromium.log";
  const std::string command = fmt::format(
      "timeout 120 /usr/bin/chromium --headless --no-sandbox --disable-gpu --disable-background-networking "
      "--disable-component-update --disable-sync --no-first-run --user-data-dir={} --enable-logging=stderr --v=0 "
      "--dump-dom file://{} 2>{}",
      (root / "profile").string(), (report / "index.html").string(), log.string());
  const std::string dom = run_and_capture(command);
  ASSERT_NE(dom.find("</html>"), std::string::npos) << "no DOM dumped; chromium log:\n"
                                                    << run_and_capture("cat " + log.string());
  EXPECT_EQ(count_matches(dom, "<tr class=\"(ok|fails)\" data-status="), 3u);
  EXPECT_EQ(count_matches(dom, "<img "), 8u);  // CPU, Vulkan, mask, heatmap for the two compared cases
  EXPECT_NE(dom.find("data-script-ready=\"yes\""), std::string::npos) << "the inline script did not finish";
  EXPECT_NE(dom.find("<pre id=\"js-errors\"></pre>"), std::string::npos) << "a script error was written into the page";
  const std::string chromium_log = run_and_capture("cat " + log.string());
  EXPECT_EQ(chromium_log.find("CONSOLE"), std::string::npos) << chromium_log;
}

}  // namespace
}  // namespace rastercmp
