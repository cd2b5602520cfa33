// docs/experiments.md's tables and the tool that keeps them equal to their commands
// (experiments/doc_tables.hpp, experiments/doc_table_renderers.hpp, `rastercmp docs update|check`):
// markers, column kinds, the comparison of measured and documented cells, the rewrite.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "experiments/doc_table_renderers.hpp"
#include "experiments/doc_tables.hpp"
#include "model/errors.hpp"
#include "tests/test_temp_dir.hpp"

namespace rastercmp::experiments {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir(const std::string& name) { return test_support::fresh_temp_dir("experiments_doc_tables_" + name); }

// A document with two tables between their markers (CRLF, an indented table, no final newline).
const char* const kDoc =
    "# Title\r\n"
    "Prose with 3 numbers.\n"
    "<!-- table: speed from: rastercmp chart speed-accuracy --quick -->\n"
    "| method | CPU ms (median) | 95% interval | host |\n"
    "|---|---|---|---|\n"
    "| exact | 3.800 | 3.700 .. 3.900 | vm |\n"
    "| fast | 0.700 | 0.650 .. 0.760 | vm |\n"
    "<!-- end table: speed -->\n"
    "Between.\n"
    "  <!-- table: sum from: rastercmp chart summary --from {chart speed-accuracy --quick} -->\n"
    "  | source | rows |\n"
    "  |---|---|\n"
    "  | a | 5 |\n"
    "  <!-- end table: sum -->\n"
    "Tail without newline";

MarkdownTable speed_measured() {
  MarkdownTable t;
  t.header = {"method", "CPU ms (median)", "95% interval", "host"};
  t.columns = {{ColumnKind::Exact, ""}, {ColumnKind::Timed, "95% interval"}, {ColumnKind::Host, ""},
               {ColumnKind::Host, ""}};
  t.rows = {{"exact", "3.750", "3.650 .. 3.850", "other"}, {"fast", "0.720", "0.700 .. 0.740", "other"}};
  return t;
}

// The message of the UsageError that `f` throws (rastercmp exits 2 on it), or "" when none.
template <typename F>
std::string usage_error(F f) {
  try {
    f();
  } catch (const UsageError& e) {
    return e.what();
  }
  return "";
}

TEST(DocTables, MarkersNameTheirTableCommandAndLines) {
  const auto markers = parse_doc_markers(kDoc, "doc.md");
  ASSERT_EQ(markers.size(), 2u);
  EXPECT_EQ(markers[0].name, "speed");
  EXPECT_EQ(markers[0].command, "rastercmp chart speed-accuracy --quick");
  EXPECT_EQ(markers[0].begin_line, 3u);
  EXPECT_EQ(markers[0].end_line, 8u);
  EXPECT_EQ(markers[1].indent, "  ");
  const MarkdownTable doc = documented_table(kDoc, markers[1], "doc.md");
  EXPECT_EQ(doc.header, (std::vector<std::string>{"source", "rows"}));
  EXPECT_EQ(doc.rows, (std::vector<std::vector<std::string>>{{"a", "5"}}));

  // A command in braces is a dependency: it runs first, once, and its output folder is the argument.
  std::vector<DocCommand> commands;
  EXPECT_EQ(add_doc_command(commands, markers[0].command, ""), 0u);
  EXPECT_EQ(add_doc_command(commands, markers[1].command, ""), 1u);
  EXPECT_EQ(add_doc_command(commands, "rastercmp  chart speed-accuracy   --quick", ""), 0u);
  ASSERT_EQ(commands.size(), 2u);
  EXPECT_EQ(commands[1].args, (std::vector<std::string>{"chart", "summary", "--from", ""}));
  EXPECT_EQ(commands[1].dependencies, (std::vector<size_t>{0, 0, 0, 1}));
  EXPECT_EQ(commands[1].key, "rastercmp chart summary --from {rastercmp chart speed-accuracy --quick}");
}

TEST(DocTables, MalformedMarkersNameTheFileLineAndWhatWasExpected) {
  const std::string no_from = "a\n<!-- table: x rastercmp sweep stability -->\n| a |\n|---|\n<!-- end table: x -->\n";
  EXPECT_NE(usage_error([&] { parse_doc_markers(no_from, "doc.md"); }).find("doc.md:2: malformed marker: expected"),
            std::string::npos);
  const std::string unclosed = "<!-- table: x from: rastercmp sweep stability -->\n| a |\n|---|\n";
  EXPECT_NE(usage_error([&] { parse_doc_markers(unclosed, "doc.md"); })
                .find("doc.md:1: expected `<!-- end table: x -->` after this marker"),
            std::string::npos);
  const std::string crossed =
      "<!-- table: x from: rastercmp sweep stability -->\n| a |\n|---|\n<!-- end table: y -->\n";
  EXPECT_NE(usage_error([&] { parse_doc_markers(crossed, "doc.md"); }).find("doc.md:4: expected `<!-- end table: x -->`"),
            std::string::npos);
  const std::string not_ours = "<!-- table: x from: make docs -->\n| a |\n|---|\n<!-- end table: x -->\n";
  EXPECT_NE(usage_error([&] { parse_doc_markers(not_ours, "doc.md"); }).find("doc.md:1:"), std::string::npos);
  const std::string twice = "<!-- table: x from: rastercmp a -->\n<!-- end table: x -->\n"
                            "<!-- table: x from: rastercmp b -->\n<!-- end table: x -->\n";
  EXPECT_NE(usage_error([&] { parse_doc_markers(twice, "doc.md"); }).find("doc.md:3: table `x` is embedded twice"),
            std::string::npos);
  const std::string ragged = "<!-- table: x from: rastercmp a -->\n| a | b |\n|---|---|\n| 1 |\n<!-- end table: x -->\n";
  const auto markers = parse_doc_markers(ragged, "doc.md");
  EXPECT_NE(usage_error([&] { documented_table(ragged, markers[0], "doc.md"); })
                .find("doc.md:4: expected 2 cells as in the header, found 1"),
            std::string::npos);
  std::vector<DocCommand> commands;
  EXPECT_NE(usage_error([&] { add_doc_command(commands, "rastercmp chart summary --from {sweep x", "doc.md:9: "); })
                .find("doc.md:9: expected `}`"),
            std::string::npos);
  EXPECT_NE(usage_error([&] { add_doc_command(commands, "rastercmp sweep x --out y", "doc.md:9: "); })
                .find("expected no --out"),
            std::string::npos);
}

TEST(DocTables, UnknownTableNamesTheMarkerAndTheTablesTheCommandWrote) {
  const fs::path out = temp_dir("doc_unknown");
  MarkdownTable written = speed_measured();
  write_markdown_table(out.string(), "speed", written);
  const auto markers = parse_doc_markers(kDoc, "doc.md");
  EXPECT_EQ(measured_table(out.string(), markers[0], "doc.md").rows, written.rows);
  const std::string message = usage_error([&] { measured_table(out.string(), markers[1], "doc.md"); });
  EXPECT_NE(message.find("doc.md:10: unknown table `sum`"), std::string::npos) << message;
  EXPECT_NE(message.find("writes speed"), std::string::npos) << message;
}

TEST(DocTables, TableFileKeepsItsColumnKinds) {
  const fs::path out = temp_dir("doc_roundtrip");
  const MarkdownTable t = speed_measured();
  write_markdown_table(out.string(), "speed", t);
  const MarkdownTable back = read_table_file((out / "tables" / "speed.md").string());
  EXPECT_EQ(back.header, t.header);
  EXPECT_EQ(back.rows, t.rows);
  ASSERT_EQ(back.columns.size(), 4u);
  EXPECT_EQ(back.columns[1].kind, ColumnKind::Timed);
  EXPECT_EQ(back.columns[1].interval_column, "95% interval");
  EXPECT_EQ(back.columns[3].kind, ColumnKind::Host);
  EXPECT_FALSE(usage_error([] { parse_table_file("| a |\n|---|\n", "t.md"); }).empty());
  EXPECT_FALSE(usage_error([] { parse_table_file("<!-- columns: timed within b -->\n| a |\n|---|\n", "t.md"); }).empty());
}

TEST(DocTables, DeterministicCellsMustBeEqualTimedIntervalsMustOverlap) {
  const auto markers = parse_doc_markers(kDoc, "doc.md");
  const MarkdownTable doc = documented_table(kDoc, markers[0], "doc.md");
  MarkdownTable measured = speed_measured();
  // exact 3.700 .. 3.900 meets 3.650 .. 3.850; fast 0.650 .. 0.760 meets 0.700 .. 0.740; host cells differ: ignored.
  EXPECT_TRUE(compare_tables("speed", doc, measured).empty());

  measured.rows[1][2] = "0.710 .. 0.740";  // the documented median 0.700 lies below, but the intervals meet
  EXPECT_TRUE(compare_tables("speed", doc, measured).empty());
  measured.rows[1][2] = "0.760 .. 0.800";  // the ends touch: not told apart
  EXPECT_TRUE(compare_tables("speed", doc, measured).empty());
  measured.rows[1][2] = "0.770 .. 0.800";  // disjoint: the runs differ
  auto drifts = compare_tables("speed", doc, measured);
  ASSERT_EQ(drifts.size(), 1u);
  EXPECT_TRUE(drifts[0].timed);
  EXPECT_EQ(drifts[0].row, "row 2 (fast)");
  EXPECT_EQ(drifts[0].column, "CPU ms (median)");
  EXPECT_EQ(drifts[0].documented, "0.700");
  // A documented row without its interval is held to the new run's interval alone.
  MarkdownTable bare = doc;
  bare.rows[1][2] = "-";
  measured.rows[1][2] = "0.710 .. 0.740";
  ASSERT_EQ(compare_tables("speed", bare, measured).size(), 1u);

  measured = speed_measured();
  measured.rows[0][0] = "exact2";  // a deterministic cell
  drifts = compare_tables("speed", doc, measured);
  ASSERT_EQ(drifts.size(), 1u);
  EXPECT_FALSE(drifts[0].timed);
  EXPECT_EQ(drifts[0].column, "method");
  EXPECT_EQ(drifts[0].documented, "exact");
  EXPECT_EQ(drifts[0].measured, "exact2");

  measured = speed_measured();
  measured.rows.pop_back();
  drifts = compare_tables("speed", doc, measured);
  ASSERT_EQ(drifts.size(), 1u);
  EXPECT_EQ(drifts[0].row, "rows");
  measured.header[0] = "entry";
  EXPECT_EQ(compare_tables("speed", doc, measured).at(0).row, "header");
}

TEST(DocTables, RewriteReplacesOnlyTheTablesBetweenMarkers) {
  const auto markers = parse_doc_markers(kDoc, "doc.md");
  MarkdownTable sum;
  sum.header = {"source", "rows"};
  sum.columns = {{ColumnKind::Exact, ""}, {ColumnKind::Exact, ""}};
  sum.rows = {{"a", "6"}, {"b", "1"}};
  const std::string out = rewrite_doc(kDoc, markers, {{"speed", speed_measured()}, {"sum", sum}}, "doc.md");
  const std::string doc = kDoc;
  auto up_to = [](const std::string& s, const std::string& marker) { return s.substr(0, s.find(marker) + marker.size()); };
  auto from = [](const std::string& s, const std::string& marker) { return s.substr(s.find(marker)); };
  const std::string begin1 = "--quick -->\n", end1 = "<!-- end table: speed -->\nBetween.\n  <!-- table: sum";
  EXPECT_EQ(up_to(out, begin1), up_to(doc, begin1));  // the \r\n of the first line survives
  EXPECT_EQ(from(out, "<!-- end table: sum -->"), "<!-- end table: sum -->\nTail without newline");
  EXPECT_NE(out.find("| exact | 3.750 | 3.650 .. 3.850 | other |\n"), std::string::npos);
  EXPECT_NE(out.find("-->\n  | source | rows |\n  |---|---|\n  | a | 6 |\n  | b | 1 |\n  <!-- end table: sum -->"),
            std::string::npos);
  EXPECT_NE(out.find(end1), std::string::npos);
  // Rewriting with the tables the document already holds changes nothing.
  std::map<std::string, MarkdownTable> same;
  for (const auto& m : markers) same[m.name] = documented_table(kDoc, m, "doc.md");
  EXPECT_EQ(rewrite_doc(kDoc, markers, same, "doc.md"), doc);
  EXPECT_NE(usage_error([&] { rewrite_doc(kDoc, markers, {{"speed", speed_measured()}}, "doc.md"); })
                .find("doc.md:10: no measured table `sum`"),
            std::string::npos);
}

TEST(DocTables, RenderersGroupEqualSeriesAndFormatValues) {
  EXPECT_EQ(table_value(316227.766), "316,228");
  EXPECT_EQ(table_value(0.0017782794), "0.00178");
  EXPECT_EQ(table_value(std::nan("")), "—");
  const fs::path out = temp_dir("doc_resolution");
  write_resolution_tables(out.string(), R"({"sizes": [64, 128], "methods": [
    {"family": "fill", "method": "fill=scanline", "predicted_exponent": 1, "measured_exponent": 1.0, "agrees": true,
     "refused": false, "points": [{"size": 64, "either": 5}, {"size": 128, "either": 10}]},
    {"family": "fill", "method": "fill=winding", "predicted_exponent": 1, "measured_exponent": 1.0, "agrees": true,
     "refused": false, "points": [{"size": 64, "either": 5}, {"size": 128, "either": 10}]},
    {"family": "fill", "method": "fill=flood", "predicted_exponent": 1, "measured_exponent": 2.0, "agrees": false,
     "refused": false, "points": [{"size": 64, "either": 1000}, {"size": 128, "either": 4000}]}]})");
  const MarkdownTable t = read_table_file((out / "tables" / "resolution.md").string());
  EXPECT_EQ(t.header, (std::vector<std::string>{"family", "method", "predicted", "measured", "holds", "64", "128"}));
  EXPECT_EQ(t.rows, (std::vector<std::vector<std::string>>{
                        {"fill", "fill=scanline, fill=winding", "1", "1.00", "yes", "5", "10"},
                        {"fill", "fill=flood", "1", "2.00", "**no**", "1,000", "4,000"}}));
}

}  // namespace
}  // namespace rastercmp::experiments
