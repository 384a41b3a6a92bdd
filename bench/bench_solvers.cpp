// Root-solver microbenchmarks: ns per call of earliest_downward_root, for each solver and scalar,
// on random collision-derived quartics and quadratics (tests/tools/solver_cases.hpp, the same
// generator as the accuracy test) and on the hard set (fixtures/polynomials/hard.json).
// Each benchmark cycles through a fixed list of polynomials, so every solver sees the same calls.
// Usage: bench_solvers [google benchmark flags], e.g. --benchmark_filter=quartics/double
//        --benchmark_repetitions=5 --benchmark_format=json. PGE_SOLVER_SEED changes the cases.
// With PGE_SOLVER_ACCURACY=FILE (the JSON that test_solvers_accuracy writes to
// $PGE_SOLVER_REPORT), it also prints the Markdown table of bench/README.md: ns per call (the
// median over repetitions) beside each solver's errors.
#include "solver_cases.hpp"

#include "pge/roots.hpp"
#include "pge/scalar.hpp"

#include <benchmark/benchmark.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#ifndef PGE_HARD_POLYNOMIALS
#error "PGE_HARD_POLYNOMIALS must name fixtures/polynomials/hard.json"
#endif

namespace {

using pge::SolverKind;

// Enough distinct polynomials that branch predictors cannot learn the sequence.
constexpr std::size_t kRandomCases = 4096;

template <class T> struct Prepared {
  pge::Poly<T> p;
  T lo, hi;
  pge::StartRule rule;
};

template <class T> std::vector<Prepared<T>> prepare(const std::vector<pge::cases::Case>& cs) {
  std::vector<Prepared<T>> out;
  using std::isfinite;
  for (const auto& c : cs) {
    Prepared<T> p{pge::cases::convert<T>(c.p), T(c.lo), T(c.hi), c.rule};
    bool finite = true;
    for (int k = 0; k <= p.p.degree; ++k) finite = finite && isfinite(p.p.c[k]);
    if (finite) out.push_back(p);  // float cannot hold the hard set's 1e100 coefficients
  }
  return out;
}

template <class T> void run(benchmark::State& state, SolverKind solver, const std::vector<pge::cases::Case>& cs) {
  const std::vector<Prepared<T>> cases = prepare<T>(cs);
  std::size_t i = 0, roots = 0;
  for (auto _ : state) {
    const Prepared<T>& c = cases[i];
    const pge::RootOutcome<T> r = pge::earliest_downward_root(solver, c.p, c.lo, c.hi, c.rule);
    benchmark::DoNotOptimize(r);
    roots += r.status == pge::RootStatus::Root;
    i = i + 1 == cases.size() ? 0 : i + 1;
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["ns_per_call"] = benchmark::Counter(static_cast<double>(state.iterations()),
                                                     benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["root_fraction"] = static_cast<double>(roots) / static_cast<double>(state.iterations());
}

template <class T> void register_scalar(const std::string& set, const std::vector<pge::cases::Case>& cs) {
  for (SolverKind solver : {SolverKind::Fast, SolverKind::Robust, SolverKind::Certified}) {
    const std::string name = set + "/" + std::string(pge::ScalarTraits<T>::name) + "/" + std::string(pge::solver_name(solver));
    benchmark::RegisterBenchmark(name.c_str(), [solver, &cs](benchmark::State& s) { run<T>(s, solver, cs); });
  }
}

// Keeps ns per call of every run, to print the table after the console report.
class TableReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& r : runs) {
      if (r.run_type != Run::RT_Iteration || r.iterations == 0) continue;
      const double ns = r.GetAdjustedCPUTime();  // per iteration, in the default time unit (ns)
      samples[r.run_name.function_name].push_back(ns);
    }
    ConsoleReporter::ReportRuns(runs);
  }
  std::map<std::string, std::vector<double>> samples;  // "set/scalar/solver" -> ns per call
};

double median(std::vector<double> v) {
  if (v.empty()) return -1;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// The Markdown table: one row per scalar and solver.
void print_table(const TableReporter& reporter, const char* accuracy_path) {
  std::ifstream in(accuracy_path);
  if (!in) {
    std::fprintf(stderr, "bench_solvers: cannot read %s\n", accuracy_path);
    return;
  }
  std::map<std::string, nlohmann::json> accuracy;
  for (const auto& row : nlohmann::json::parse(in)) accuracy[row.at("key").get<std::string>()] = row;
  auto ns = [&](const std::string& key) {
    const auto it = reporter.samples.find(key);
    return it == reporter.samples.end() ? -1.0 : median(it->second);
  };
  std::printf("\n| scalar | solver | ns quartic | ns quadratic | ns hard set | random: median / largest ulps | random: missed + invented | hard: median / largest ulps | hard: missed + invented | certified not correctly rounded |\n");
  std::printf("| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
  for (const char* scalar : {"float", "double", "long double", "quad"}) {
    for (const char* solver : {"fast", "robust", "certified"}) {
      const std::string tail = std::string(scalar) + "/" + solver;
      const nlohmann::json empty = nlohmann::json::object();
      const auto& random = accuracy.count(tail + "/random") ? accuracy[tail + "/random"] : empty;
      const auto& hard = accuracy.count(tail + "/hard") ? accuracy[tail + "/hard"] : empty;
      auto num = [](const nlohmann::json& j, const char* k) { return j.contains(k) ? j[k].get<double>() : -1.0; };
      std::printf("| %s | %s | %.0f | %.0f | %.0f | %.3g / %.3g | %.0f + %.0f | %.3g / %.3g | %.0f + %.0f | %s |\n", scalar, solver,
                  ns("quartics/" + tail), ns("quadratics/" + tail), ns("hard/" + tail), num(random, "median_ulps"),
                  num(random, "largest_ulps"), num(random, "misses"), num(random, "invented"), num(hard, "median_ulps"),
                  num(hard, "largest_ulps"), num(hard, "misses"), num(hard, "invented"),
                  std::string(solver) == "certified"
                      ? std::to_string(static_cast<long>(num(random, "certified_wrong") + num(hard, "certified_wrong"))).c_str()
                      : "-");
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  const std::uint64_t seed = pge::cases::seed_from_env();
  static const std::vector<pge::cases::Case> quartics = pge::cases::random_cases(seed, kRandomCases, true);
  static const std::vector<pge::cases::Case> quadratics = pge::cases::random_cases(seed + 1, kRandomCases, false);
  static const std::vector<pge::cases::Case> hard = [] {
    std::vector<pge::cases::Case> cs;
    for (const auto& h : pge::cases::load_hard_set(PGE_HARD_POLYNOMIALS)) cs.push_back(h.c);
    return cs;
  }();
  for (const auto* set : {&quartics, &quadratics, &hard}) {
    const std::string name = set == &quartics ? "quartics" : (set == &quadratics ? "quadratics" : "hard");
    register_scalar<float>(name, *set);
    register_scalar<double>(name, *set);
    register_scalar<long double>(name, *set);
    register_scalar<pge::Quad>(name, *set);
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 2;
  TableReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  if (const char* accuracy = std::getenv("PGE_SOLVER_ACCURACY")) print_table(reporter, accuracy);
  benchmark::Shutdown();
  return 0;
}
