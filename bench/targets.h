#pragma once
// The benchmark's targets, kept as data (bench/targets.json) and checked against the suite
// results by one generic evaluator, so that a target changes in the data file, not in code.
//
// A target (every field but rows, ratio, stage, each_stage and context is required):
//   id, description, source    what it is and which issue set it
//   select                     {"suite", "section", filters...}: the timing entries it reads;
//                              filters: size ("1920x1080"), scene, method, mode, threads,
//                              iterations, feedback_tap, levels, key
//   rows                       [{"label", "select": {filters...}, "ratio": {...}}]: one verdict
//                              a row, each row's filters over the target's (a row may change the
//                              section); a row's ratio filters go over the target's ratio's
//   metric                     a JSON pointer into the selected entry ("/frame_ms/filter/median")
//   ratio                      {"numerator": {filters}, "denominator": {filters}}: the metric
//                              of one entry over another's (each may name its own section)
//   stage                      a stage name: metric and context point into that stage of the
//                              entry (of both entries of a ratio)
//   each_stage                 {pointer: value}: one verdict per stage of the entry whose
//                              fields match; metric and context point into the stage
//   comparator, threshold      "<=" or ">=" a number, or "in" [low, high]
//   unit, digits               how the measured value is written
//   context                    [{"label", "metric", "unit", "digits"}]: shown beside the value
#include <string>
#include <vector>

#include "bench/results.h"

namespace svgf::bench {

enum class Verdict { Met, Missed, NotMeasured };
const char* to_string(Verdict v);

// A number with how to write it.
struct Reading {
  std::string label;
  double value = NAN;
  std::string unit;
  int digits = 2;
};

// One row of the targets table.
struct TargetResult {
  std::string id;
  std::string target;  // the description, the row or stage, the comparison
  std::string source;
  Reading measured;  // NaN when not measured
  std::vector<Reading> context;
  Verdict verdict = Verdict::NotMeasured;
};

// Reads the targets file; a missing or malformed file, or a target with an unknown or missing
// field, is an error naming the file (and the target).
json load_targets(const std::string& path);

// Every target against the results, in file order (each target's rows in theirs).
std::vector<TargetResult> evaluate_targets(const json& targets, const Results& r);

}  // namespace svgf::bench
