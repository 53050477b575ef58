// The repose test's studies (aggpack/study), when the module is built with the physics module:
// repose() (one run, or a seed ensemble with seeds=...) and sweep(), as `aggpack repose [--seeds]`
// and `aggpack sweep` run them, with a progress callback per finished run and cancelling (the
// callback returning False, an exception raised in it, or Ctrl-C: runs not yet started are
// skipped). Results as dicts.

#include <pybind11/stl.h>

#include <atomic>
#include <cstdint>
#include <exception>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bindings.h"

#ifdef AGGPACK_HAS_SIM
#include "aggpack/config/repose_config.h"
#include "aggpack/core/error.h"
#include "aggpack/sim/distributed.h"
#include "aggpack/sim/ensemble.h"
#include "aggpack/sim/repose.h"
#include "aggpack/sim/sweep.h"
#include "aggpack/study/repose_study.h"
#include "aggpack/study/run_parts.h"
#endif

namespace aggpack::python {

#ifdef AGGPACK_HAS_SIM
namespace {

py::dict study_fit_dict(const SlopeFit& fit) {
  py::dict d;
  d["is_valid"] = fit.is_valid;
  d["message"] = fit.message;
  d["angle_degrees"] = fit.angle_degrees;
  d["slope"] = fit.slope;
  d["intercept"] = fit.intercept;
  d["r_squared"] = fit.r_squared;
  d["pile_height"] = fit.pile_height;
  d["first_bin"] = fit.first_bin;
  d["last_bin"] = fit.last_bin;
  return d;
}

std::shared_ptr<PyPacking> study_packing(Packing packing) {
  auto result = std::make_shared<PyPacking>();
  result->packing = std::move(packing);
  return result;
}

// Sweep options from None / dict / TOML text, with the CLI's keys and messages.
SweepOptions study_options(const py::object& config, const std::vector<std::string>& overrides) {
  std::string text;
  std::string source = "config";
  if (py::isinstance<py::dict>(config)) {
    // The same dict -> TOML conversion as PackConfig.from_dict.
    text = py::module_::import("aggpack").attr("_dict_to_toml")(config).cast<std::string>();
    source = "config dict";
  } else if (py::isinstance<py::str>(config)) {
    text = config.cast<std::string>();
  } else if (!config.is_none()) {
    throw InvalidInput("config", py::repr(config).cast<std::string>(),
                       "None (the paper's case), a dict or a TOML string");
  }
  // Notes (a former table name, [particles]) as FutureWarnings, before any error.
  std::vector<std::string> notes;
  const auto warn = [&notes] {
    for (const std::string& note : notes) {
      if (PyErr_WarnEx(PyExc_FutureWarning, note.c_str(), 1) != 0) throw py::error_already_set();
    }
  };
  SweepOptions options;
  try {
    options = parse_sweep_config(text, source, overrides, &notes);
  } catch (const Error&) {
    warn();
    throw;
  }
  warn();
  // Everything a run checks before it starts, before records= makes its folder.
  with_sweep_key_names([&] {
    validate(options);
    study::check_repose_inputs(options.base);
  });
  return options;
}

// The seeds of `seeds=`: None keeps the configuration's (ensemble.seeds; none: one run), an int
// n the seeds 1..n, a str the CLI's --seeds syntax ("1-4,9"), a sequence of ints those seeds.
std::vector<std::uint64_t> study_seeds(const py::object& seeds, std::vector<std::uint64_t> given) {
  if (seeds.is_none()) return given;
  if (py::isinstance<py::bool_>(seeds)) {
    throw InvalidInput("seeds", py::repr(seeds).cast<std::string>(),
                       "None, a count, a list of seeds or a range such as \"1-16\"");
  }
  if (py::isinstance<py::int_>(seeds)) {
    const auto count = seeds.cast<long long>();
    if (count < 1 || count > static_cast<long long>(kMaxEnsembleSeeds)) {
      throw InvalidInput("seeds", std::to_string(count),
                         "a count in [1, " + std::to_string(kMaxEnsembleSeeds) + "]");
    }
    return parse_seed_list("1-" + std::to_string(count), "seeds");
  }
  if (py::isinstance<py::str>(seeds)) return parse_seed_list(seeds.cast<std::string>(), "seeds");
  if (!py::isinstance<py::sequence>(seeds)) {
    throw InvalidInput("seeds", py::repr(seeds).cast<std::string>(),
                       "None, a count, a list of seeds or a range such as \"1-16\"");
  }
  std::string text;
  for (const py::handle item : seeds) {
    const bool is_integer = py::isinstance<py::int_>(item) && !py::isinstance<py::bool_>(item);
    if (!is_integer || py::reinterpret_borrow<py::int_>(item) < py::int_(0) ||
        py::reinterpret_borrow<py::int_>(item) >
            py::int_(std::numeric_limits<std::uint64_t>::max())) {
      throw InvalidInput("seeds", py::repr(item).cast<std::string>(),
                         "non-negative integers below 2^64");
    }
    text += (text.empty() ? "" : ",") + py::str(item).cast<std::string>();
  }
  return parse_seed_list(text, "seeds");  // empty, repeated or too many: its messages
}

// Calls the Python callback (if any) after each finished run and checks for Ctrl-C, holding the
// GIL only for that. The first exception (or a False return) sets `cancel`: no further run
// starts; the exception is kept for the caller.
struct StudyBridge {
  py::object callback;
  std::atomic<bool> cancel{false};
  std::exception_ptr error;

  template <class MakeDict>
  void operator()(const MakeDict& make_dict) {
    if (cancel.load()) return;
    const py::gil_scoped_acquire gil;
    try {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      if (!callback.is_none()) {
        const py::object answer = callback(make_dict());
        if (py::isinstance<py::bool_>(answer) && !answer.cast<bool>()) cancel.store(true);
      }
    } catch (...) {
      error = std::current_exception();
      cancel.store(true);
    }
  }
};

py::object or_none(bool has_value, double value) {
  return has_value ? py::object(py::float_(value)) : py::object(py::none());
}

py::dict ensemble_dict(const EnsembleResult& ensemble) {
  py::list seeds;
  std::vector<double> angles;
  for (const EnsembleSeed& s : ensemble.seeds) {
    py::dict d;
    d["seed"] = s.seed;
    d["is_valid"] = s.is_valid;
    d["angle_degrees"] = s.angle_degrees;
    d["r_squared"] = s.r_squared;
    d["is_at_rest"] = s.is_at_rest;
    d["particle_count"] = s.particle_count;
    d["error"] = s.error;
    seeds.append(d);
    angles.push_back(s.is_valid ? s.angle_degrees : std::numeric_limits<double>::quiet_NaN());
  }
  const EnsembleStatistics& st = ensemble.statistics;
  py::dict statistics;  // the keys of ensemble.json's "statistics"
  statistics["seeds_total"] = ensemble.seeds.size();
  statistics["seeds_used"] = st.count;
  statistics["seeds_failed"] = ensemble.failed_count();
  statistics["mean_angle_degrees"] = or_none(st.count > 0, st.mean);
  statistics["std_dev_degrees"] = or_none(st.has_interval, st.std_dev);
  statistics["confidence"] = 0.95;
  statistics["t_quantile"] = or_none(st.has_interval, st.t_quantile);
  statistics["ci_half_width_degrees"] = or_none(st.has_interval, st.half_width);
  statistics["ci_lower_degrees"] = or_none(st.has_interval, st.lower());
  statistics["ci_upper_degrees"] = or_none(st.has_interval, st.upper());
  py::dict d;
  d["angle_degrees"] = or_none(st.count > 0, st.mean);
  d["angles"] = to_numpy(std::move(angles));
  d["seeds"] = seeds;
  d["statistics"] = statistics;
  d["is_cancelled"] = ensemble.is_cancelled;
  return d;
}

py::dict single_run_dict(ReposeResult& result) {
  py::dict d;
  d["angle_degrees"] = result.fit.angle_degrees;
  d["fit"] = study_fit_dict(result.fit);
  d["particle_count"] = result.particle_count;
  d["solid_volume"] = result.solid_volume;
  d["mean_measured_alpha"] = result.mean_measured_alpha;
  d["time_step"] = result.time_step;
  d["is_stage1_at_rest"] = result.is_stage1_at_rest;
  d["stage1_time"] = result.stage1_time;
  d["is_stage2_at_rest"] = result.is_stage2_at_rest;
  d["stage2_time"] = result.stage2_time;
  d["baffle_travel"] = result.baffle_travel;
  d["escaped_particles"] = result.escaped_particles;
  py::dict profile;
  std::vector<double> x(result.profile.height.size());
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = result.profile.centre(i);
  profile["x"] = to_numpy(std::move(x));
  profile["height"] = to_numpy(std::vector<double>(result.profile.height));
  d["profile"] = profile;
  d["initial"] = study_packing(std::move(result.initial));
  d["settled"] = study_packing(std::move(result.settled));
  d["final"] = study_packing(std::move(result.final));
  return d;
}

py::dict sweep_case_dict(const SweepCase& c) {
  py::dict d;
  d["index"] = c.index;
  d["alpha"] = c.alpha;
  d["friction"] = c.friction;
  d["mean_measured_alpha"] = c.mean_measured_alpha;
  d["particle_count"] = c.particle_count;
  d["is_valid"] = c.is_valid;
  d["angle_degrees"] = c.angle_degrees;
  d["r_squared"] = c.r_squared;
  d["is_at_rest"] = c.is_at_rest;
  d["simulated_time"] = c.simulated_time;
  d["seed"] = c.seed;
  if (c.seed_count > 1) {
    d["seed_count"] = c.seed_count;
    d["seeds_used"] = c.seeds_used;
    d["std_dev_degrees"] = c.statistics.std_dev;
    d["ci_lower_degrees"] = c.statistics.lower();
    d["ci_upper_degrees"] = c.statistics.upper();
  }
  return d;
}

std::string fmt_share(const RunShare& share) {
  return "(" + std::to_string(share.worker) + ", " + std::to_string(share.of) + ")";
}

// share=(K, N): worker K of N (1-based), as the CLI's --case K --of N.
RunShare study_share(const py::object& share) {
  if (share.is_none()) return {};
  const auto refuse = [&] {
    throw InvalidInput(
        "share", py::repr(share).cast<std::string>(),
        "None or (K, N): worker K of N, 1 <= K <= N <= " + std::to_string(kMaxWorkers));
  };
  if (!py::isinstance<py::tuple>(share) && !py::isinstance<py::list>(share)) refuse();
  const auto items = share.cast<py::sequence>();
  if (items.size() != 2) refuse();
  std::size_t values[2] = {0, 0};
  for (std::size_t k = 0; k < 2; ++k) {
    const py::object item = items[k];
    if (!py::isinstance<py::int_>(item) || py::isinstance<py::bool_>(item) ||
        item.cast<py::int_>() < py::int_(1) || item.cast<py::int_>() > py::int_(kMaxWorkers)) {
      refuse();
    }
    values[k] = item.cast<std::size_t>();
  }
  if (values[0] > values[1]) refuse();
  return RunShare{values[0], values[1]};
}

// records=FOLDER (and share): the run records of this call's runs, for merge(). A record that
// cannot be written cancels the runs; the first such error is kept for the caller.
struct StudyRecords {
  std::optional<study::RunRecorder> recorder;
  std::exception_ptr error;
  template <class Run>
  void record(const Run& run, StudyBridge& bridge) {
    if (!recorder || error) return;
    try {
      recorder->record(run);
    } catch (...) {
      error = std::current_exception();
      bridge.cancel.store(true);
    }
  }
};

StudyRecords study_records(RunKind kind, const SweepOptions& options, const py::object& records,
                           const RunShare& share) {
  StudyRecords out;
  if (records.is_none()) {
    if (share.is_split()) {
      throw InvalidInput("share", fmt_share(share),
                         "with records=FOLDER (a share's runs are summed up by merge(FOLDER))");
    }
    return out;
  }
  if (!py::isinstance<py::str>(records) || records.cast<std::string>().empty()) {
    throw InvalidInput("records", py::repr(records).cast<std::string>(),
                       "None or a folder name (str)");
  }
  const std::string folder = records.cast<std::string>();
  with_sweep_key_names([&] { out.recorder.emplace(kind, options, folder, 0, "records"); });
  return out;
}

py::object run_repose_call(const py::object& config, const std::vector<std::string>& overrides,
                           const py::object& seeds_given, const py::object& progress,
                           const py::object& share_given, const py::object& records_given) {
  SweepOptions options = study_options(config, overrides);
  options.seeds = study_seeds(seeds_given, options.seeds);
  const RunShare share = study_share(share_given);
  if (options.seeds.empty()) {
    if (!progress.is_none()) {
      throw InvalidInput("progress", "a callable", "None for one run (progress needs seeds=...)");
    }
    if (!records_given.is_none() || share.is_split()) {
      throw InvalidInput(
          records_given.is_none() ? "share" : "records",
          records_given.is_none() ? fmt_share(share) : py::repr(records_given).cast<std::string>(),
          "None for one run (a run in parts needs seeds=...)");
    }
    std::optional<ReposeResult> result;
    {
      const py::gil_scoped_release release;
      // physics.engine = "yade" runs YADE (aggpack/sim/repose_yade.h)
      with_sweep_key_names([&] { result = study::run_repose(options.base); });
    }
    return single_run_dict(*result);
  }
  StudyRecords records = study_records(RunKind::kEnsemble, options, records_given, share);
  StudyBridge bridge;
  bridge.callback = progress;
  study::StudyControl control;
  control.cancel = &bridge.cancel;
  control.share = &share;
  control.on_seed = [&bridge, &records](const EnsembleSeed& s, const ReposeResult*,
                                        std::size_t done, std::size_t total) {
    records.record(s, bridge);
    bridge([&] {
      py::dict d;
      d["done"] = done;
      d["total"] = total;
      d["seed"] = s.seed;
      d["is_valid"] = s.is_valid;
      d["angle_degrees"] = s.angle_degrees;
      d["error"] = s.error;
      return d;
    });
  };
  std::optional<EnsembleResult> ensemble;
  {
    const py::gil_scoped_release release;
    with_sweep_key_names(
        [&] { ensemble = study::run_repose_ensemble(options.base, options.seeds, control); });
  }
  if (records.error) std::rethrow_exception(records.error);
  if (bridge.error) std::rethrow_exception(bridge.error);
  return ensemble_dict(*ensemble);
}

py::list run_sweep_call(const py::object& config, const std::vector<std::string>& overrides,
                        const py::object& seeds_given, const py::object& progress,
                        const py::object& share_given, const py::object& records_given) {
  SweepOptions options = study_options(config, overrides);
  options.seeds = study_seeds(seeds_given, options.seeds);
  const RunShare share = study_share(share_given);
  StudyRecords records = study_records(RunKind::kSweep, options, records_given, share);
  StudyBridge bridge;
  bridge.callback = progress;
  study::StudyControl control;
  control.cancel = &bridge.cancel;
  control.share = &share;
  control.on_run = [&bridge, &records](const SweepCase& c, const ReposeResult&, std::size_t done,
                                       std::size_t total) {
    records.record(c, bridge);
    bridge([&] {
      py::dict d;
      d["done"] = done;
      d["total"] = total;
      d["alpha"] = c.alpha;
      d["friction"] = c.friction;
      d["seed"] = c.seed;
      d["is_valid"] = c.is_valid;
      d["angle_degrees"] = c.angle_degrees;
      return d;
    });
  };
  std::optional<study::SweepResult> result;
  {
    const py::gil_scoped_release release;
    with_sweep_key_names([&] {
      if (share.is_split()) {
        result.emplace();
        study::SweepRuns runs = study::run_sweep_runs(options, control);
        result->cases = std::move(runs.runs);
        result->is_cancelled = runs.is_cancelled;
      } else {
        result = study::run_sweep(options, control);
      }
    });
  }
  if (records.error) std::rethrow_exception(records.error);
  if (bridge.error) std::rethrow_exception(bridge.error);
  py::list rows;
  for (const SweepCase& c : result->cases) rows.append(sweep_case_dict(c));
  return rows;
}

// aggpack.merge(folder): the workers' run records merged, as `aggpack merge` (no files written).
py::object merge_call(const std::string& folder) {
  std::optional<study::MergedRuns> merged;
  {
    const py::gil_scoped_release release;
    merged = study::merge_runs(folder);
  }
  if (merged->kind == RunKind::kEnsemble) return ensemble_dict(merged->ensemble);
  py::list rows;
  for (const SweepCase& c : merged->cases) rows.append(sweep_case_dict(c));
  return rows;
}

}  // namespace
#endif

void register_study(py::module_& m) {
#ifdef AGGPACK_HAS_SIM
  m.def("repose", &run_repose_call, py::arg("config") = py::none(),
        py::arg("overrides") = std::vector<std::string>{}, py::kw_only(),
        py::arg("seeds") = py::none(), py::arg("progress") = py::none(),
        py::arg("share") = py::none(), py::arg("records") = py::none(),
        R"doc(The angle-of-repose trough test, as `aggpack repose [CONFIG.toml] --set ...`: the
paper's lattice fill behind the baffle, stage 1 settles it, stage 2 moves the baffle away, the
pile's slope is fitted. config: None (the paper's case), a dict or TOML text with the tables of
docs/config.md ([trough] [particle] [physics] [rest] [measure]); overrides: "key=value" strings.
Releases the GIL; minutes for the paper's 1,050 particles.

One run (seeds None and no ensemble.seeds in the config): returns a dict: angle_degrees, fit
(is_valid, angle_degrees, slope, r_squared, pile_height, ...), particle_count, solid_volume m^3,
mean_measured_alpha, stage times (s), profile {x, height} (m, float64 arrays), and the packings
initial, settled, final.

A seed ensemble, as `aggpack repose --seeds`: seeds = a count n (seeds 1..n), a list of seeds or
the CLI's syntax ("1-4,9"); the runs go side by side, each seed's result the same as its own
single run. Returns a dict: angle_degrees (the mean over valid seeds, None if none), angles
(float64 array, one per seed in the given order, NaN where the run failed), seeds (one dict per
seed: seed, is_valid, angle_degrees, r_squared, is_at_rest, particle_count, error), statistics
(the keys of ensemble.json: seeds_used, mean_angle_degrees, std_dev_degrees, t_quantile,
ci_lower_degrees, ci_upper_degrees of the 95 % interval, ...; None without an interval) and
is_cancelled. progress: None or a callable progress(dict) called after each finished seed with
done, total, seed, is_valid, angle_degrees, error. Returning False cancels: seeds not yet started
are skipped and the result holds the seeds that ran (is_cancelled True). An exception raised by
the callback also cancels and is re-raised; Ctrl-C is checked after each seed.

In parts, as `aggpack repose --seeds ... --case K --of N`: records = a folder: every finished seed
leaves its run record in records/runs/ (a folder holding records of another configuration is
refused); share = (K, N) runs only worker K's seeds (seed i of the list belongs to worker
(i mod N) + 1) and needs records. When every worker is done, merge(records) (or `aggpack merge`)
gives the ensemble.
Raises ConfigError naming the key, InvalidInput naming `seeds`, `share` or `records`.)doc");

  m.def("sweep", &run_sweep_call, py::arg("config") = py::none(),
        py::arg("overrides") = std::vector<std::string>{}, py::kw_only(),
        py::arg("seeds") = py::none(), py::arg("progress") = py::none(),
        py::arg("share") = py::none(), py::arg("records") = py::none(),
        R"doc(The repose test over every (alpha, mu_s) case, as `aggpack sweep` (config and
overrides as repose(), plus the [sweep] table: alphas, frictions). Returns one dict per case in
index order: alpha, friction, angle_degrees, r_squared, is_valid, is_at_rest, particle_count,
mean_measured_alpha, simulated_time, seed. seeds (as repose()): a seed ensemble per case, whose
angle_degrees is then the mean over the seeds, with seed_count, seeds_used, std_dev_degrees,
ci_lower_degrees and ci_upper_degrees. progress: called after each finished run (done, total,
alpha, friction, seed, is_valid, angle_degrees); returning False cancels: runs not yet started
are skipped and sweep() returns one dict per run that ran instead of the table. share and
records: a sweep in parts, as repose()'s (run i = case i / seeds, seed i % seeds); with share
(K, N), N > 1, sweep() returns one dict per run of the share instead of the table. Releases the
GIL; long for the paper's 65 cases.)doc");

  m.def(
      "merge", &merge_call, py::arg("folder"),
      R"doc(The summary of an ensemble or sweep run in parts, as `aggpack merge FOLDER` (which also
writes the summary files; this call writes nothing): reads FOLDER/runs/*.json, the records the
workers (`aggpack repose --seeds ... --case K --of N`, `aggpack sweep --case K --of N`, or mpirun
ranks) left, checks they are one configuration and complete, and returns what repose(seeds=...)
returns for an ensemble (a dict) or what sweep() returns for a sweep (one dict per case).
Raises InvalidInput naming the missing runs and the worker that owns them, FormatError for a file
that is not a run record.)doc");
#else
  (void)m;
#endif
}

}  // namespace aggpack::python
