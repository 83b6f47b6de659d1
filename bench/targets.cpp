#include "bench/targets.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <stdexcept>

namespace svgf::bench {
namespace {

const std::set<std::string> kFields = {
    "id",    "description", "source",     "select",    "rows", "metric", "ratio",
    "stage", "each_stage",  "comparator", "threshold", "unit", "digits", "context"};
const char* const kRequired[] = {"id",     "description", "source",   "select",
                                 "metric", "comparator",  "threshold"};

// Where a filter's value sits in a timing entry (size, suite and section are not fields).
const std::map<std::string, std::string> kFilterFields = {{"scene", "/input/scene"},
                                                          {"method", "/config/method"},
                                                          {"mode", "/config/mode"},
                                                          {"threads", "/config/threads"},
                                                          {"iterations", "/config/iterations"},
                                                          {"feedback_tap", "/config/feedback_tap"},
                                                          {"levels", "/config/levels"},
                                                          {"key", "/key"}};

bool is_filter(const std::string& name) {
  return name == "suite" || name == "section" || name == "size" || kFilterFields.count(name);
}

// Throws `what` about target `t` of the file.
struct Checker {
  const std::string& path;
  std::string id;
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error(path + ": " + (id.empty() ? "" : "target \"" + id + "\": ") + what);
  }
  void require(bool ok, const std::string& what) const {
    if (!ok) fail(what);
  }
  void filters(const json& f, const std::string& where) const {
    require(f.is_object(), where + " is not an object");
    for (const auto& [name, value] : f.items())
      require(is_filter(name), where + ": unknown filter \"" + name + "\"");
  }
  void pointer(const json& p, const std::string& where) const {
    require(p.is_string(), where + " is not a JSON pointer string");
    try {
      json::json_pointer ptr(p.get<std::string>());
    } catch (const json::exception& e) {
      fail(where + " is not a JSON pointer: " + e.what());
    }
  }
  void ratio(const json& r, const std::string& where) const {
    require(r.is_object(), where + " is not an object");
    for (const auto& [name, value] : r.items())
      require(name == "numerator" || name == "denominator",
              where + ": unknown field \"" + name + "\"");
    for (const char* part : {"numerator", "denominator"})
      if (r.contains(part)) filters(r[part], where + " " + part);
  }
  void readings(const json& t) const {
    require(!t.contains("unit") || t["unit"].is_string(), "unit is not a string");
    require(!t.contains("digits") ||
                (t["digits"].is_number_integer() && t["digits"] >= 0 && t["digits"] <= 9),
            "digits is not a whole number from 0 to 9");
  }
};

void check_target(const Checker& c, const json& t) {
  for (const auto& [name, value] : t.items())
    c.require(kFields.count(name), "unknown field \"" + name + "\"");
  for (const char* f : kRequired) c.require(t.contains(f), std::string("no \"") + f + "\"");
  c.require(t["description"].is_string() && t["source"].is_string(),
            "description and source must be strings");
  c.filters(t["select"], "select");
  c.require(t["select"].contains("suite") && t["select"].contains("section"),
            "select needs a suite and a section");
  if (t.contains("rows")) {
    c.require(t["rows"].is_array() && !t["rows"].empty(), "rows is not a non-empty list");
    for (const json& row : t["rows"]) {
      c.require(row.is_object() && row.value("label", json()).is_string(), "a row without a label");
      const std::string where = "row \"" + row["label"].get<std::string>() + "\"";
      for (const auto& [name, value] : row.items())
        c.require(name == "label" || name == "select" || name == "ratio",
                  where + ": unknown field \"" + name + "\"");
      c.filters(row.value("select", json::object()), where);
      if (row.contains("ratio")) {
        c.require(t.contains("ratio"), where + " has a ratio but the target has none");
        c.ratio(row["ratio"], where + " ratio");
      }
    }
  }
  c.pointer(t["metric"], "metric");
  if (t.contains("ratio")) {
    c.require(t["ratio"].contains("numerator") && t["ratio"].contains("denominator"),
              "ratio needs a numerator and a denominator");
    c.ratio(t["ratio"], "ratio");
    c.require(!t.contains("each_stage") && !t.contains("context"),
              "a ratio takes neither each_stage nor context");
  }
  if (t.contains("stage"))
    c.require(t["stage"].is_string() && !t.contains("each_stage"),
              "stage is not a name, or comes with each_stage");
  if (t.contains("each_stage")) {
    c.require(t["each_stage"].is_object(), "each_stage is not an object");
    for (const auto& [p, v] : t["each_stage"].items()) c.pointer(p, "each_stage field");
  }
  const json& cmp = t["comparator"];
  const json& th = t["threshold"];
  c.require(cmp == "<=" || cmp == ">=" || cmp == "in", "comparator is not <=, >= or in");
  if (cmp == "in")
    c.require(
        th.is_array() && th.size() == 2 && th[0].is_number() && th[1].is_number() && th[0] <= th[1],
        "threshold of \"in\" is not [low, high]");
  else
    c.require(th.is_number(), "threshold is not a number");
  c.readings(t);
  if (t.contains("context")) {
    c.require(t["context"].is_array(), "context is not a list");
    for (const json& x : t["context"]) {
      c.require(x.is_object() && x.contains("metric"), "a context entry without a metric");
      c.pointer(x["metric"], "context metric");
      c.readings(x);
    }
  }
}

json merged(json a, const json& b) {
  for (const auto& [k, v] : b.items()) a[k] = v;
  return a;
}

bool matches(const json& e, const json& filters) {
  for (const auto& [name, value] : filters.items()) {
    if (name == "suite" || name == "section") continue;
    if (name == "size") {
      if (size_of(e) != value) return false;
      continue;
    }
    const json::json_pointer p(kFilterFields.at(name));
    if (!e.contains(p) || e[p] != value) return false;
  }
  return true;
}

// The one entry `filters` select, nullptr when none; several are an error (the target is
// ambiguous).
const json* select_one(const Results& r, const json& filters, const std::string& id) {
  const json* found = nullptr;
  for (const json* e : r.timings(filters["suite"], filters["section"])) {
    if (!matches(*e, filters)) continue;
    if (found)
      throw std::runtime_error("target \"" + id + "\": more than one entry matches " +
                               filters.dump() + " (" + (*found)["label"].get<std::string>() + ", " +
                               (*e)["label"].get<std::string>() + ")");
    found = e;
  }
  return found;
}

// What metric and context point into: the entry, or its stage named by the target's "stage"
// (nullptr when the entry has no such stage).
const json* measured_in(const json& e, const json& t) {
  if (!t.contains("stage")) return &e;
  for (const json& s : e["stages"])
    if (s.value("stage", "") == t["stage"]) return &s;
  return nullptr;
}

double value_at(const json& obj, const json& pointer) {
  const json::json_pointer p(pointer.get<std::string>());
  return obj.contains(p) ? num(obj[p]) : NAN;
}

Reading reading(const json& spec, double value) {
  Reading r;
  r.label = spec.value("label", "");
  r.value = value;
  r.unit = spec.value("unit", "");
  r.digits = spec.value("digits", 2);
  return r;
}

Verdict judge(const json& t, double v) {
  if (!std::isfinite(v)) return Verdict::NotMeasured;
  const json& th = t["threshold"];
  bool ok;
  if (t["comparator"] == "<=")
    ok = v <= th.get<double>();
  else if (t["comparator"] == ">=")
    ok = v >= th.get<double>();
  else
    ok = v >= th[0].get<double>() && v <= th[1].get<double>();
  return ok ? Verdict::Met : Verdict::Missed;
}

std::string number(double v) {
  char s[32];
  std::snprintf(s, sizeof s, "%g", v);
  return s;
}

// "≤ 0.3 ms", "≥ 60%", "in [3.6, 4.4]×".
std::string requirement(const json& t) {
  const std::string unit = t.value("unit", "");
  const json& th = t["threshold"];
  if (t["comparator"] == "in")
    return "in [" + number(th[0].get<double>()) + ", " + number(th[1].get<double>()) + "]" + unit;
  return (t["comparator"] == "<=" ? "≤ " : "≥ ") + number(th.get<double>()) + unit;
}

}  // namespace

const char* to_string(Verdict v) {
  switch (v) {
    case Verdict::Met:
      return "met";
    case Verdict::Missed:
      return "missed";
    default:
      return "not measured";
  }
}

json load_targets(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot read the targets file");
  json doc = json::parse(in, nullptr, false);
  const Checker file{path, ""};
  file.require(!doc.is_discarded(), "the targets file is not valid JSON");
  file.require(doc.is_object() && doc.contains("targets") && doc["targets"].is_array(),
               "the targets file has no \"targets\" list");
  std::set<std::string> ids;
  for (const json& t : doc["targets"]) {
    file.require(t.is_object() && t.contains("id") && t["id"].is_string(),
                 "a target without an id");
    const Checker c{path, t["id"].get<std::string>()};
    c.require(ids.insert(c.id).second, "the id is used twice");
    check_target(c, t);
  }
  return doc["targets"];
}

std::vector<TargetResult> evaluate_targets(const json& targets, const Results& r) {
  std::vector<TargetResult> out;
  for (const json& t : targets) {
    const std::string id = t["id"].get<std::string>();
    const json rows = t.value("rows", json::array({json{{"label", ""}}}));
    for (const json& row : rows) {
      const json select = merged(t["select"], row.value("select", json::object()));
      const std::string label = row["label"].get<std::string>();
      const size_t before = out.size();
      // One result row: `name` (row label, stage) in parentheses after the description.
      auto add = [&](const std::string& name, double value, const json* context_of) {
        TargetResult res;
        res.id = id;
        res.target = t["description"].get<std::string>() + (name.empty() ? "" : " (" + name + ")") +
                     " " + requirement(t);
        res.source = t["source"].get<std::string>();
        res.measured = reading(t, value);
        if (context_of)
          for (const json& c : t.value("context", json::array()))
            res.context.push_back(reading(c, value_at(*context_of, c["metric"])));
        res.verdict = judge(t, value);
        out.push_back(res);
      };
      if (t.contains("ratio")) {
        const json row_ratio = row.value("ratio", json::object());
        auto part = [&](const char* name) {
          const json* e = select_one(
              r,
              merged(merged(select, t["ratio"][name]), row_ratio.value(name, json::object())),
              id);
          return e ? measured_in(*e, t) : nullptr;
        };
        const json* a = part("numerator");
        const json* b = part("denominator");
        add(label, a && b ? value_at(*a, t["metric"]) / value_at(*b, t["metric"]) : NAN, nullptr);
        continue;
      }
      const json* found = select_one(r, select, id);
      const json* e = found ? measured_in(*found, t) : nullptr;
      if (e && t.contains("each_stage")) {
        for (const json& stage : (*e)["stages"]) {
          bool all = true;
          for (const auto& [p, v] : t["each_stage"].items()) {
            const json::json_pointer ptr(p);
            all = all && stage.contains(ptr) && stage[ptr] == v;
          }
          if (all)
            add((label.empty() ? "" : label + ", ") + stage.value("stage", "?"),
                value_at(stage, t["metric"]), &stage);
        }
      } else if (e) {
        add(label, value_at(*e, t["metric"]), e);
      }
      if (out.size() == before) add(label, NAN, nullptr);  // nothing measured it
    }
  }
  return out;
}

}  // namespace svgf::bench
