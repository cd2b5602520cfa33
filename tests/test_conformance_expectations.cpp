// Baseline logic (expected fail, unexpected improvement, flakes, skips), case selection and
// interleaved sharding of compare/expectations + compare/case_select.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cstdlib>
#include <set>

#include "compare/case_select.hpp"
#include "compare/expectations.hpp"
#include "model/errors.hpp"

namespace rastercmp {
namespace {

Expectations mesa_style() {
  Expectations e;
  e.baseline = parse_baseline(
      "# known differences, one reason per line\n"
      "rastercmp.depth.bias.d16,Fail\n"
      "\n"
      "rastercmp.msaa.depth,InternalError\n"
      "rastercmp.line.wide,QualityWarning\n",
      "fails.txt");
  e.flakes = parse_patterns("# flaky\nrastercmp\\.flaky\\..*\n", "flakes.txt");
  e.skips = parse_patterns("^rastercmp\\.slow\\.\n", "skips.txt");
  return e;
}

TEST(Baseline, ParsesNamesStatusesAndComments) {
  const Expectations e = mesa_style();
  EXPECT_EQ(e.baseline.size(), 3u);
  EXPECT_EQ(e.expected("rastercmp.depth.bias.d16"), "Fail");
  EXPECT_EQ(e.expected("rastercmp.msaa.depth"), "Fail");  // a CTS name, read as deqp-runner's
  EXPECT_EQ(e.expected("rastercmp.line.wide"), "Warn");
  EXPECT_EQ(e.expected("rastercmp.not.listed"), "Pass");
}

TEST(Baseline, TakesDeqpRunnerStatusesAsWritten) {
  const auto b = parse_baseline(
      "a,Crash\nb,Timeout\nc,Missing\nd,Skip\ne,UnexpectedImprovement(Pass)\nf,ExpectedFail\ng,NotSupported\n", "f");
  EXPECT_EQ(b.at("a"), "Crash");
  EXPECT_EQ(b.at("b"), "Timeout");
  EXPECT_EQ(b.at("c"), "Missing");
  EXPECT_EQ(b.at("d"), "Skip");
  EXPECT_EQ(b.at("e"), "UnexpectedImprovement(Pass)");
  EXPECT_EQ(b.at("f"), "ExpectedFail");
  EXPECT_EQ(b.at("g"), "Skip");
  EXPECT_THROW(parse_baseline("a,UnexpectedImprovement(Nope)\n", "f"), InputError);
}

// deqp-runner's RunnerStatus::with_baseline, case by case (its own unit test's cases among them).
TEST(Outcome, WithBaselineIsDeqpRunners) {
  EXPECT_EQ(with_baseline("Pass", ""), "Pass");
  EXPECT_EQ(with_baseline("Fail", ""), "Fail");
  EXPECT_EQ(with_baseline("Crash", ""), "Crash");
  EXPECT_EQ(with_baseline("Fail", "Fail"), "ExpectedFail");
  EXPECT_EQ(with_baseline("Crash", "Crash"), "ExpectedFail");
  EXPECT_EQ(with_baseline("Timeout", "Timeout"), "ExpectedFail");
  EXPECT_EQ(with_baseline("Pass", "Fail"), "UnexpectedImprovement(Pass)");
  EXPECT_EQ(with_baseline("Fail", "Crash"), "UnexpectedImprovement(Fail)");
  EXPECT_EQ(with_baseline("Fail", "Timeout"), "UnexpectedImprovement(Fail)");
  EXPECT_EQ(with_baseline("Pass", "Timeout"), "UnexpectedImprovement(Pass)");
  EXPECT_EQ(with_baseline("Fail", "ExpectedFail"), "ExpectedFail");
  EXPECT_EQ(with_baseline("Crash", "ExpectedFail"), "ExpectedFail");
  EXPECT_EQ(with_baseline("Pass", "Missing"), "UnexpectedImprovement(Pass)");
  EXPECT_EQ(with_baseline("Warn", "Fail"), "UnexpectedImprovement(Warn)");
  EXPECT_EQ(with_baseline("Warn", "Warn"), "ExpectedFail");
  EXPECT_EQ(with_baseline("Skip", "Crash"), "UnexpectedImprovement(Skip)");
  EXPECT_EQ(with_baseline("Crash", "Fail"), "Crash");
  EXPECT_EQ(with_baseline("Timeout", "Fail"), "Timeout");
  EXPECT_EQ(with_baseline("Pass", "Skip"), "Pass");
  for (const char* s : {"Pass", "Skip", "Warn", "Flake", "KnownFlake", "ExpectedFail"})
    EXPECT_TRUE(is_success_status(s));
  for (const char* s : {"Fail", "Crash", "Timeout", "Missing", "UnexpectedImprovement(Pass)"})
    EXPECT_FALSE(is_success_status(s)) << s;
}

TEST(Outcome, VerdictsBecomeDeqpRunnerStatuses) {
  EXPECT_EQ(runner_status(Verdict::Pass), "Pass");
  EXPECT_EQ(runner_status(Verdict::Fail), "Fail");
  EXPECT_EQ(runner_status(Verdict::QualityWarning), "Warn");
  EXPECT_EQ(runner_status(Verdict::NotSupported), "Skip");
  EXPECT_EQ(runner_status(Verdict::ResourceError), "Fail");
  EXPECT_EQ(runner_status(Verdict::InternalError), "Fail");
  EXPECT_EQ(runner_status(Verdict::Crash), "Crash");
  EXPECT_EQ(runner_status(Verdict::Timeout), "Timeout");
}

TEST(Baseline, TheCommentAboveAnEntryIsItsReason) {
  const auto reasons = parse_baseline_reasons(
      "# header, not a reason\n"
      "\n"
      "# no tie rule:\n"
      "#   both sides fill\n"
      "a.fan,Fail\n"
      "b.plain,Fail\n"
      "# detached by a blank line\n"
      "\n"
      "c.other,Fail\n");
  EXPECT_EQ(reasons.size(), 1u);
  EXPECT_EQ(reasons.at("a.fan"), "no tie rule: both sides fill");
  Expectations e;
  e.reasons = reasons;
  EXPECT_EQ(e.reason("a.fan"), "no tie rule: both sides fill");
  EXPECT_EQ(e.reason("b.plain"), "");
}

TEST(Baseline, MalformedLinesNameTheFileAndLine) {
  try {
    parse_baseline("a,Fail\nb Fail\n", "fails.txt");
    FAIL() << "a line without a comma was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "fails.txt");
    EXPECT_EQ(e.json_path(), "line 2");
  }
  EXPECT_THROW(parse_baseline("a,Crashed\n", "fails.txt"), InputError);
  EXPECT_THROW(parse_baseline("a,Fail\na,Fail\n", "fails.txt"), InputError);
  EXPECT_THROW(parse_patterns("ok\n(unclosed\n", "flakes.txt"), InputError);
}

// std::regex recurses: a pattern long or nested enough overflowed the stack (SIGSEGV). Such lines
// are bad input naming the file and line; nesting inside a bracket or escaped does not count.
TEST(Expectations, PatternsAreBoundedBeforeTheyAreCompiled) {
  const auto problem = [](const std::string& text) -> std::string {
    try {
      parse_patterns(text, "skips.txt");
    } catch (const InputError& e) {
      return e.json_path() + ": " + e.what();
    }
    return "";
  };
  EXPECT_NE(problem(std::string(100000, 'a') + "\n").find("at most 1000 characters, found 100000"), std::string::npos);
  EXPECT_NE(problem("ok\n" + std::string(30000, '(') + std::string(30000, ')') + "\n").find("line 2"),
            std::string::npos);
  EXPECT_NE(problem(std::string(17, '(') + "a" + std::string(17, ')') + "\n").find("nested at most 16 groups deep"),
            std::string::npos);
  EXPECT_EQ(problem(std::string(16, '(') + "a" + std::string(16, ')') + "\n"), "");
  EXPECT_EQ(problem("[((((((((((((((((((]" + std::string(20, '\\') + "\n"), "");
  EXPECT_EQ(problem(std::string(1000, 'a') + "\n"), "");
}

TEST(Outcome, PassAndExpectedFailDoNotFailTheRun) {
  const Expectations e = mesa_style();
  const Outcome pass = judge_outcome("rastercmp.fill.a", Verdict::Pass, e);
  EXPECT_EQ(pass.status, "Pass");
  EXPECT_FALSE(pass.fails_run);
  const Outcome expected_fail = judge_outcome("rastercmp.depth.bias.d16", Verdict::Fail, e);
  EXPECT_EQ(expected_fail.status, "ExpectedFail");
  EXPECT_FALSE(expected_fail.fails_run);
  const Outcome expected_error = judge_outcome("rastercmp.msaa.depth", Verdict::InternalError, e);
  EXPECT_EQ(expected_error.status, "ExpectedFail");
  EXPECT_FALSE(expected_error.fails_run);
}

TEST(Outcome, NewFailuresFailTheRun) {
  const Expectations e = mesa_style();
  const Outcome fail = judge_outcome("rastercmp.fill.a", Verdict::Fail, e);
  EXPECT_EQ(fail.status, "Fail");
  EXPECT_TRUE(fail.fails_run);
  // Every CTS error is deqp-runner's Fail, so an expected Fail covers them ...
  EXPECT_EQ(judge_outcome("rastercmp.depth.bias.d16", Verdict::ResourceError, e).status, "ExpectedFail");
  // ... but not a crash.
  const Outcome crash = judge_outcome("rastercmp.depth.bias.d16", Verdict::Crash, e);
  EXPECT_EQ(crash.status, "Crash");
  EXPECT_TRUE(crash.fails_run);
  EXPECT_TRUE(judge_outcome("rastercmp.fill.a", Verdict::Timeout, e).fails_run);
}

TEST(Outcome, NewlyPassingExpectedFailureIsAnUnexpectedImprovementThatFails) {
  const Expectations e = mesa_style();
  const Outcome improved = judge_outcome("rastercmp.depth.bias.d16", Verdict::Pass, e);
  EXPECT_EQ(improved.status, "UnexpectedImprovement(Pass)");
  EXPECT_TRUE(improved.fails_run);
  const Outcome warned = judge_outcome("rastercmp.msaa.depth", Verdict::QualityWarning, e);
  EXPECT_EQ(warned.status, "UnexpectedImprovement(Warn)");
  EXPECT_TRUE(warned.fails_run);
}

TEST(Outcome, WarningsAndUnsupportedAreNotFailures) {
  const Expectations e = mesa_style();
  EXPECT_FALSE(judge_outcome("rastercmp.fill.a", Verdict::QualityWarning, e).fails_run);
  EXPECT_FALSE(judge_outcome("rastercmp.fill.a", Verdict::NotSupported, e).fails_run);
  EXPECT_EQ(judge_outcome("rastercmp.fill.a", Verdict::NotSupported, e).status, "Skip");
  EXPECT_EQ(judge_outcome("rastercmp.fill.a", Verdict::QualityWarning, e).status, "Warn");
  const Outcome better = judge_outcome("rastercmp.line.wide", Verdict::Pass, e);
  EXPECT_EQ(better.status, "Pass");
  EXPECT_FALSE(better.fails_run);
}

TEST(Outcome, FlakesNeverFailTheRun) {
  const Expectations e = mesa_style();
  const Outcome flake = judge_outcome("rastercmp.flaky.one", Verdict::Fail, e);
  EXPECT_EQ(flake.status, "KnownFlake");
  EXPECT_FALSE(flake.fails_run);
  EXPECT_EQ(judge_outcome("rastercmp.flaky.one", Verdict::Pass, e).status, "Pass");
  // The pattern matches anywhere in the name (deqp-runner's regex is_match).
  EXPECT_TRUE(matches_any(e.flakes, "x.rastercmp.flaky.y"));
  EXPECT_FALSE(matches_any(e.flakes, "rastercmp.flakyness"));
}

SuiteCase named(const std::string& name) { return SuiteCase{name, name + ".json", Scene{}}; }

std::vector<std::string> names_of(const std::vector<SuiteCase>& cases) {
  std::vector<std::string> names;
  for (const SuiteCase& c : cases) names.push_back(c.name);
  return names;
}

TEST(Selection, CaselistGlobsAndSkipsNarrowTheSuiteInOrder) {
  const std::vector<SuiteCase> suite = {named("rastercmp.fill.a"), named("rastercmp.fill.b"), named("rastercmp.line.a"),
                                        named("rastercmp.slow.big")};
  const Expectations e = mesa_style();
  EXPECT_EQ(names_of(select_cases(suite, CaseFilter{{}, {}, e.skips}, "")),
            (std::vector<std::string>{"rastercmp.fill.a", "rastercmp.fill.b", "rastercmp.line.a"}));
  EXPECT_EQ(names_of(select_cases(suite, CaseFilter{{}, {"*.a", "rastercmp.slow.*"}, e.skips}, "")),
            (std::vector<std::string>{"rastercmp.fill.a", "rastercmp.line.a"}));
  const auto list = parse_caselist("# resume\nrastercmp.line.a\n\n  rastercmp.fill.b \n");
  EXPECT_EQ(names_of(select_cases(suite, CaseFilter{list, {}, {}}, "list.txt")),
            (std::vector<std::string>{"rastercmp.fill.b", "rastercmp.line.a"}));
  EXPECT_THROW(select_cases(suite, CaseFilter{{"rastercmp.nope"}, {}, {}}, "list.txt"), InputError);
}

TEST(Selection, GlobIsShellStyle) {
  EXPECT_TRUE(glob_match("rastercmp.fill.*", "rastercmp.fill.top_left.shared_edge"));
  EXPECT_TRUE(glob_match("*.shared_?dge", "rastercmp.fill.shared_edge"));
  EXPECT_FALSE(glob_match("rastercmp.line.*", "rastercmp.fill.a"));
}

TEST(Shard, InterleavesCases) {
  EXPECT_EQ(shard_positions(10, Shard{0, 3}), (std::vector<size_t>{0, 3, 6, 9}));
  EXPECT_EQ(shard_positions(10, Shard{1, 3}), (std::vector<size_t>{1, 4, 7}));
  EXPECT_EQ(shard_positions(10, Shard{2, 3}), (std::vector<size_t>{2, 5, 8}));
  EXPECT_TRUE(shard_positions(2, Shard{2, 3}).empty());
  const std::vector<SuiteCase> suite = {named("a"), named("b"), named("c"), named("d"), named("e")};
  EXPECT_EQ(names_of(take_shard(suite, Shard{1, 2})), (std::vector<std::string>{"b", "d"}));
}

TEST(Shard, ParsesIOfNAndRejectsTheRest) {
  EXPECT_EQ(parse_shard("0/1"), (Shard{0, 1}));
  EXPECT_EQ(parse_shard("3/4"), (Shard{3, 4}));
  for (const char* bad : {"4/4", "1/0", "1", "a/2", "-1/2", "1/2/3", "", "1/"})
    EXPECT_THROW(parse_shard(bad), UsageError) << bad;
}

TEST(Shard, ComesFromTheGoogleTestEnvironment) {
  unsetenv("GTEST_SHARD_INDEX");
  unsetenv("GTEST_TOTAL_SHARDS");
  EXPECT_FALSE(shard_from_environment().has_value());
  setenv("GTEST_SHARD_INDEX", "2", 1);
  setenv("GTEST_TOTAL_SHARDS", "5", 1);
  EXPECT_EQ(shard_from_environment(), (Shard{2, 5}));
  setenv("GTEST_SHARD_INDEX", "5", 1);
  EXPECT_THROW(shard_from_environment(), UsageError);
  unsetenv("GTEST_SHARD_INDEX");
  unsetenv("GTEST_TOTAL_SHARDS");
}

// The shards of any split are disjoint and together hold every case once.
RC_GTEST_PROP(ShardProperty, ShardsPartitionTheCases, ()) {
  const size_t n = *rc::gen::inRange<size_t>(0, 200);
  const uint32_t count = *rc::gen::inRange<uint32_t>(1, 17);
  std::multiset<size_t> seen;
  for (uint32_t index = 0; index < count; ++index)
    for (size_t p : shard_positions(n, Shard{index, count})) {
      RC_ASSERT(p % count == index);
      seen.insert(p);
    }
  RC_ASSERT(seen.size() == n);
  for (size_t p = 0; p < n; ++p) RC_ASSERT(seen.count(p) == 1u);
}

}  // namespace
}  // namespace rastercmp
