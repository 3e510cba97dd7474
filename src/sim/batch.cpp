// Simulator::run_batch: many runs of one trajectory on a few std::threads, each run's samples
// kept as the request's channels at its rows and their extremes, the parameter sets made run by
// run on the thread that runs them.

#include "pamkit/sim/batch.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <limits>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <thread>
#include <type_traits>

#include "pamkit/sim/simulator.hpp"

namespace pamkit {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
/// Samples per block a batch's run hands over: one block holds every column of them, per thread.
constexpr std::size_t kBatchBlockSize = 4096;

/// The setter of field `field` of the structure `select(params, start)` returns, if `Struct`
/// lists a number of that name.
template <class Struct, class Select>
std::function<void(MuscleParams&, InitialState&, double)> field_setter(const std::string& field, Select select) {
  std::function<void(MuscleParams&, InitialState&, double)> setter;
  Struct::for_each_field([&](const char* name, auto Struct::*member, const FieldInfo&) {
    using Value = std::remove_reference_t<decltype(std::declval<Struct&>().*member)>;
    if constexpr (std::is_same_v<Value, double>) {
      if (field == name) {
        setter = [select, member](MuscleParams& params, InitialState& start, double value) {
          select(params, start).*member = value;
        };
      }
    }
  });
  return setter;
}

/// The setter behind one of ParameterSets' names (see its constructor); empty if there is none.
std::function<void(MuscleParams&, InitialState&, double)> setter_for(const std::string& name) {
  const auto dot = name.find('.');
  if (dot == std::string::npos) return {};
  const std::string area = name.substr(0, dot);
  const std::string field = name.substr(dot + 1);
  if (area == "build") {
    return field_setter<MuscleBuild>(field, [](MuscleParams& p, InitialState&) -> MuscleBuild& { return p.build; });
  }
  if (area == "friction") {
    return field_setter<FrictionParams>(field,
                                        [](MuscleParams& p, InitialState&) -> FrictionParams& { return p.friction; });
  }
  if (area == "gas") {
    return field_setter<GasParams>(field, [](MuscleParams& p, InitialState&) -> GasParams& { return p.gas; });
  }
  if (area == "extensions") {
    return field_setter<ModelExtensions>(
        field, [](MuscleParams& p, InitialState&) -> ModelExtensions& { return p.extensions; });
  }
  if (area == "initial") {
    return field_setter<InitialState>(field, [](MuscleParams&, InitialState& s) -> InitialState& { return s; });
  }
  if (name == "bladder.shear_modulus_Pa") {
    return [](MuscleParams& p, InitialState&, double value) { p.bladder = BladderLaw::neo_hookean(value); };
  }
  return {};
}

/// Runs run(r, workspace) for every r < runs on `threads` threads, the calling one among them,
/// each with a workspace of its own from make_workspace() and taking the next run as it finishes
/// one: which thread runs which run changes nothing but the time.
/// \throws the first exception a run let out, after every thread has stopped.
template <class MakeWorkspace, class Run>
void for_each_run(std::size_t runs, std::size_t threads, const MakeWorkspace& make_workspace, const Run& run) {
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  threads = std::min(threads, runs);
  std::atomic<std::size_t> next{0};
  std::mutex failure_lock;
  std::exception_ptr failure;
  const auto work = [&] {
    auto workspace = make_workspace();
    for (std::size_t r = next++; r < runs; r = next++) {
      try {
        run(r, workspace);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(failure_lock);
        if (!failure) failure = std::current_exception();
        next = runs;  // the others stop after their run
      }
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(threads > 0 ? threads - 1 : 0);
  try {
    for (std::size_t i = 1; i < threads; ++i) pool.emplace_back(work);
  } catch (...) {
    next = runs;
    for (std::thread& thread : pool) thread.join();
    throw;
  }
  work();
  for (std::thread& thread : pool) thread.join();
  if (failure) std::rethrow_exception(failure);
}

/// The request checked against the trajectory, and the columns of its channels.
struct CheckedRequest {
  const BatchRequest& request;
  std::vector<std::vector<double> SimulationResult::*> columns;

  CheckedRequest(const BatchRequest& batch, const ElongationTrajectory& trajectory) : request(batch) {
    for (const std::string& channel : batch.channels) {
      std::vector<double> SimulationResult::*found = nullptr;
      std::string known;
      SimulationResult::for_each_column(
          [&](const char* name, std::vector<double> SimulationResult::*member, const char*, const char*, bool output) {
            if (!output) return;
            known += (known.empty() ? "" : ", ") + std::string(name);
            if (channel == name) found = member;
          });
      if (!found) {
        throw InvalidInput(
            detail::message("Simulator.run_batch: unknown channel '", channel, "' (known: ", known, ")"));
      }
      if (std::find(columns.begin(), columns.end(), found) != columns.end()) {
        throw InvalidInput(detail::message("Simulator.run_batch: channel '", channel, "' is asked for twice"));
      }
      columns.push_back(found);
    }
    for (std::size_t i = 0; i < batch.rows.size(); ++i) {
      if (batch.rows[i] >= trajectory.size()) {
        throw InvalidInput(detail::message("Simulator.run_batch: rows[", i, "] = ", batch.rows[i],
                                           " is past the trajectory's last sample (", trajectory.size() - 1, ")"));
      }
      if (i > 0 && !(batch.rows[i] > batch.rows[i - 1])) {
        throw InvalidInput(detail::message("Simulator.run_batch: rows[", i, "] = ", batch.rows[i],
                                           " does not increase (rows[", i - 1, "] = ", batch.rows[i - 1], ")"));
      }
    }
  }

  /// A result for `runs` runs, every value NaN until its run fills it.
  BatchResult sized(std::size_t runs) const {
    BatchResult result;
    result.runs = runs;
    result.channels = request.channels;
    result.rows = request.rows;
    const std::size_t channels = columns.size();
    result.values.assign(channels, std::vector<double>(runs * request.rows.size(), kNaN));
    result.maximum.assign(channels, std::vector<double>(runs, kNaN));
    result.minimum.assign(channels, std::vector<double>(runs, kNaN));
    result.statistics.resize(runs);
    result.errors.resize(runs);
    result.failures.assign(runs, RunFailure::none);
    return result;
  }
};

/// What one thread carries from run to run: the run it records, where in its rows it is, and
/// its extremes so far. The result's arrays are shared, each run writing its own entries only.
class BatchWorkspace {
 public:
  BatchWorkspace(const CheckedRequest& checked, BatchResult& result) : checked_(checked), result_(result) {}

  /// Run r of `model` along `motion` into the result: its statistics and samples, or its error.
  void run(const Simulator& simulator, std::size_t r, const MuscleModel& model, const ElongationTrajectory& motion,
           const ShapeTable* shapes) {
    run_ = r;
    next_row_ = 0;
    const std::size_t channels = checked_.columns.size();
    highest_.assign(channels, -std::numeric_limits<double>::infinity());
    lowest_.assign(channels, std::numeric_limits<double>::infinity());
    const auto sink = [this](std::size_t first, const SimulationResult& block) { record(first, block); };
    try {
      result_.statistics[r] = simulator.run_blocks(model, motion, kBatchBlockSize, sink, shapes);
    } catch (const SolverError& error) {
      fail(r, error.what(), RunFailure::solver);
      return;
    } catch (const Error& error) {
      fail(r, error.what(), RunFailure::input);
      return;
    }
    for (std::size_t c = 0; c < channels; ++c) {
      result_.maximum[c][r] = highest_[c];
      result_.minimum[c][r] = lowest_[c];
    }
  }

  /// Marks run r failed with `message`: NaN where it wrote, zero counters.
  void fail(std::size_t r, const std::string& message, RunFailure failure) {
    const std::size_t width = checked_.request.rows.size();
    for (std::vector<double>& values : result_.values) {
      std::fill(values.begin() + static_cast<std::ptrdiff_t>(r * width),
                values.begin() + static_cast<std::ptrdiff_t>((r + 1) * width), kNaN);
    }
    result_.statistics[r] = SolverStatistics{};
    result_.errors[r] = message;
    result_.failures[r] = failure;
  }

 private:
  /// One block of run_'s samples: the kept rows it holds, and the extremes over all of them (a
  /// NaN, once seen, stays: numpy's max and min propagate it).
  void record(std::size_t first, const SimulationResult& block) {
    const std::vector<std::size_t>& rows = checked_.request.rows;
    const std::size_t count = block.time_s.size();
    for (std::size_t c = 0; c < checked_.columns.size(); ++c) {
      const std::vector<double>& column = block.*checked_.columns[c];
      double& highest = highest_[c];
      double& lowest = lowest_[c];
      for (const double value : column) {
        if (!std::isnan(highest) && !(value <= highest)) highest = value;
        if (!std::isnan(lowest) && !(value >= lowest)) lowest = value;
      }
    }
    for (; next_row_ < rows.size() && rows[next_row_] < first + count; ++next_row_) {
      for (std::size_t c = 0; c < checked_.columns.size(); ++c) {
        result_.values[c][run_ * rows.size() + next_row_] = (block.*checked_.columns[c])[rows[next_row_] - first];
      }
    }
  }

  const CheckedRequest& checked_;
  BatchResult& result_;
  std::size_t run_ = 0;
  std::size_t next_row_ = 0;
  std::vector<double> highest_;
  std::vector<double> lowest_;
};

}  // namespace

ParameterSets::ParameterSets(MuscleParams base, InitialState start, bool inflated_start, std::vector<std::string> names,
                             std::vector<double> values)
    : base_(std::move(base)),
      start_(start),
      inflated_start_(inflated_start),
      names_(std::move(names)),
      values_(std::move(values)) {
  if (names_.empty()) throw InvalidInput("ParameterSets: no field names: a run sets at least one");
  if (values_.size() % names_.size() != 0) {
    throw InvalidInput(detail::message("ParameterSets: ", values_.size(), " values are not a whole number of runs of ",
                                       names_.size(), " fields"));
  }
  runs_ = values_.size() / names_.size();
  for (std::size_t i = 0; i < names_.size(); ++i) {
    const std::string& name = names_[i];
    if (std::find(names_.begin(), names_.begin() + static_cast<std::ptrdiff_t>(i), name) !=
        names_.begin() + static_cast<std::ptrdiff_t>(i)) {
      throw InvalidInput(detail::message("ParameterSets: field '", name, "' is named twice"));
    }
    if (name == "build.braid_angle_deg") {
      braid_angle_ = static_cast<std::ptrdiff_t>(i);
      setters_.emplace_back();
      continue;
    }
    setters_.push_back(setter_for(name));
    if (!setters_.back()) {
      throw InvalidInput(detail::message(
          "ParameterSets: '", name,
          "' is not a field a run can set (build.<MuscleBuild field>, build.braid_angle_deg, "
          "bladder.shear_modulus_Pa, friction.<field>, gas.<field>, extensions.<field>, initial.length_m, "
          "initial.gauge_pressure_Pa: numbers only)"));
    }
    sets_length_ = sets_length_ || name == "initial.length_m";
  }
  if (braid_angle_ >= 0 && std::find(names_.begin(), names_.end(), "build.fiber_revolutions") != names_.end()) {
    throw InvalidInput("ParameterSets: build.braid_angle_deg and build.fiber_revolutions say the same: name one");
  }
}

std::pair<MuscleParams, InitialState> ParameterSets::at(std::size_t run) const {
  if (run >= runs_) throw std::out_of_range(detail::message("ParameterSets.at: run ", run, " of ", runs_));
  MuscleParams params = base_;
  InitialState start = start_;
  const double* values = values_.data() + run * names_.size();
  for (std::size_t i = 0; i < names_.size(); ++i) {
    if (setters_[i]) setters_[i](params, start, values[i]);
  }
  // The revolutions follow from the angle through the build's other dimensions, set above.
  if (braid_angle_ >= 0) {
    params.build.fiber_revolutions =
        fiber_revolutions_for_braid_angle(params.build, values[static_cast<std::size_t>(braid_angle_)]);
  }
  params.validate();
  if (inflated_start_ && !sets_length_) start = inflated_and_sealed(params, start.gauge_pressure_Pa);
  return {params, start};
}

BatchResult Simulator::run_batch(const std::vector<MuscleModel>& models, const ElongationTrajectory& trajectory,
                                 const BatchRequest& request, const ShapeTable* shapes,
                                 const std::vector<ElongationTrajectory>& motions) const {
  const CheckedRequest checked(request, trajectory);
  if (!motions.empty() && motions.size() != models.size()) {
    throw InvalidInput(detail::message("Simulator.run_batch: ", motions.size(), " motions for ", models.size(),
                                       " models (give none, or one each)"));
  }
  for (std::size_t i = 0; i < motions.size(); ++i) {
    if (motions[i].time() != trajectory.time()) {
      throw InvalidInput(
          detail::message("Simulator.run_batch: motion ", i, " is not sampled at the trajectory's times"));
    }
  }
  BatchResult result = checked.sized(models.size());
  for_each_run(
      models.size(), request.threads, [&] { return BatchWorkspace(checked, result); },
      [&](std::size_t r, BatchWorkspace& workspace) {
        workspace.run(*this, r, models[r], motions.empty() ? trajectory : motions[r], shapes);
      });
  return result;
}

BatchResult Simulator::run_batch(const ParameterSets& sets, const ElongationTrajectory& trajectory,
                                 const BatchRequest& request) const {
  const CheckedRequest checked(request, trajectory);
  BatchResult result = checked.sized(sets.runs());
  for_each_run(
      sets.runs(), request.threads, [&] { return BatchWorkspace(checked, result); },
      [&](std::size_t r, BatchWorkspace& workspace) {
        std::optional<std::pair<MuscleParams, InitialState>> muscle;
        try {
          muscle = sets.at(r);
        } catch (const Error& error) {
          workspace.fail(r, error.what(), RunFailure::parameters);
          return;
        }
        std::optional<MuscleModel> model;
        try {
          model.emplace(muscle->first, muscle->second);
        } catch (const Error& error) {
          workspace.fail(r, error.what(), RunFailure::input);  // a start outside the braid's range
          return;
        }
        workspace.run(*this, r, *model, trajectory, nullptr);
      });
  return result;
}

}  // namespace pamkit
