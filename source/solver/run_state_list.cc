#include <deal.II/base/mpi.h>

#include <stabilized_lagrangian/solver/contact_problem.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace StabilizedLagrangian
{
  // The run's state, listed once (RunState): what a step cut restores and a
  // checkpoint keeps. Checkpoint (solver/checkpoint.h) adds the problem's own
  // entries through the view ContactProblem::checkpoint_view() builds here.
  // Each entry checks what it reads from a checkpoint, which is untrusted
  // input (source/solver/checkpoint.cc); the mesh the state lives on (its
  // refinements) is the checkpoint's own header.

  namespace
  {
    using Scope = RunState::Scope;

    bool
    all_finite(const std::vector<double> &values)
    {
      return std::all_of(
          values.begin(), values.end(), [](const double x) { return std::isfinite(x); });
    }

    /** Whether the entries of the point or tensor @p t are finite (and not beyond 1e150). */
    template <typename T>
    bool
    finite_tensor(const T &t)
    {
      return std::isfinite(t.norm_square());
    }

    bool
    finite_work(const WorkCounters &w)
    {
      return std::isfinite(w.amg_setup_seconds + w.schur_seconds + w.krylov_seconds +
                           w.schur_solve_seconds);
    }

    /** The accumulated slip: whole entries, keys and steps in their integer ranges. */
    template <int dim>
    bool
    valid_slips(const std::vector<double> &slips)
    {
      const unsigned int entry = 3 * dim + 3;
      if (slips.size() % entry != 0 || !all_finite(slips))
        return false;
      for (std::size_t i = 0; i < slips.size(); i += entry)
        {
          for (unsigned int d = 0; d < dim; ++d)
            if (std::abs(slips[i + d]) >= 9e18) // (within std::int64_t)
              return false;
          if (slips[i + dim] < 0. || slips[i + dim] > std::numeric_limits<unsigned int>::max())
            return false;
        }
      return true;
    }

    /** A .pvd record as write_vtu_with_pvtu_record() names it: solution_<step>.pvtu. */
    bool
    is_solution_record(const std::string &name)
    {
      const std::string stem = "solution_", extension = ".pvtu";
      return name.size() > stem.size() + extension.size() && name.rfind(stem, 0) == 0 &&
             name.compare(name.size() - extension.size(), extension.size(), extension) == 0 &&
             is_decimal_number(
                 name.substr(stem.size(), name.size() - stem.size() - extension.size()), 9);
    }

    /** The entries @p owned of @p vector, in the order of the index set. */
    std::vector<double>
    owned_values(const TrilinosWrappers::MPI::Vector &vector, const IndexSet &owned)
    {
      std::vector<double> values;
      for (const auto index : owned)
        values.push_back(vector(index));
      return values;
    }

    /** Put @p values (owned_values()) into @p vector (collective). */
    void
    set_owned_values(TrilinosWrappers::MPI::Vector &vector,
                     const IndexSet                &owned,
                     const std::vector<double>     &values)
    {
      unsigned int k = 0;
      for (const auto index : owned)
        vector(index) = values[k++];
      vector.compress(VectorOperation::insert);
    }
  } // namespace

  template <int dim>
  typename Checkpoint<dim>::View
  ContactProblem<dim>::checkpoint_view()
  {
    return typename Checkpoint<dim>::View{
        mpi_communicator,
        pcout,
        state_list,
        parameters_used,
        adaptive_refinement,
        load_stepping.end_time,
        chosen,
        contact_zones,
        run_directory,
        output_directory,
        cycle,
        triangulation,
        refinement_history,
        n_u,
        n_multipliers,
        locally_owned,
        contact_quadrature,
        time,
        controller,
        work,
        path_start_work,
        last_normal_force,
        last_step_size,
        solution,
        ghosted_solution,
        step_start,
        last_increment,
        material_history,
        contact,
        active_set,
        cumulative_slip,
        solution_output,
        statistics,
        [this]() { update_ghosts(); },
        [this]() { setup_after_refinement(); },
        [this](const unsigned int k) { return refinement_cycles.directory(k); },
        [this]() { return StepStatisticsCollector<dim>(statistics_view()).supports(); }};
  }

  template <int dim>
  void
  Checkpoint<dim>::register_run_state()
  {
    register_load_stepping_state();
    register_field_state();
    register_contact_state();
    register_output_state();
  }

  template <int dim>
  void
  Checkpoint<dim>::register_load_stepping_state()
  {
    RunState &state_list = view.state_list;
    state_list.add_value<double>("time",
                                 view.time,
                                 Scope::step_cut_and_checkpoint,
                                 [](const double t) { return std::isfinite(t) && t >= 0.; });
    // the load stepping changes only when a step is accepted or cut
    state_list.add_value<LoadStepController::State>(
        "load stepping", view.controller, Scope::checkpoint_only, LoadStepController::valid);
    state_list.add_value<WorkCounters>("work", view.work, Scope::checkpoint_only, finite_work);
    state_list.add_value<WorkCounters>(
        "work before the load path", view.path_start_work, Scope::checkpoint_only, finite_work);
    state_list.add_value<double>("last normal force",
                                 view.last_normal_force,
                                 Scope::checkpoint_only,
                                 [](const double f) { return std::isfinite(f); });
    state_list.add_value<double>("last step size",
                                 view.last_step_size,
                                 Scope::checkpoint_only,
                                 [](const double h) { return std::isfinite(h) && h >= 0.; });
  }

  template <int dim>
  void
  Checkpoint<dim>::register_field_state()
  {
    RunState &state_list = view.state_list;
    // the solution's owned entries; its ghosts follow
    state_list.add(
        "solution",
        Scope::step_cut_and_checkpoint,
        [this](StateWriter &out) { out.put(owned_values(view.solution, view.locally_owned)); },
        [this](StateReader &in) -> std::function<void()> {
          auto values = in.get_finite("solution values", view.locally_owned.n_elements());
          return [this, values]() {
            set_owned_values(view.solution, view.locally_owned, values);
            view.update_ghosts();
            view.step_start = view.ghosted_solution;
          };
        },
        RunState::copy_of(view.solution));
    // the predictor's slope (`Predictor = extrapolation`), set when a step is accepted
    state_list.add(
        "last increment",
        Scope::checkpoint_only,
        [this](StateWriter &out) {
          out.put(owned_values(view.last_increment, view.locally_owned));
        },
        [this](StateReader &in) -> std::function<void()> {
          auto values = in.get_finite("increment values", view.locally_owned.n_elements());
          return [this, values]() {
            set_owned_values(view.last_increment, view.locally_owned, values);
          };
        });
    // an attempt writes only trial values, committed when the step converges
    // (Materials::QuadratureHistory::commit())
    state_list.add(
        "material history",
        Scope::checkpoint_only,
        [this](StateWriter &out) { out.put(view.material_history.committed_data()); },
        [this](StateReader &in) -> std::function<void()> {
          auto values = in.get_finite("material history values",
                                      view.material_history.committed_data().size());
          return [this, values]() { view.material_history.restore(values); };
        });
  }

  template <int dim>
  void
  Checkpoint<dim>::register_contact_state()
  {
    RunState &state_list = view.state_list;
    // the faces' segments, the points' and the conditions' states
    view.contact.register_state(state_list);
    state_list.add(
        "active set",
        Scope::checkpoint_only,
        [this](StateWriter &out) { out.put(view.active_set); },
        [this](StateReader &in) -> std::function<void()> {
          std::vector<Point<dim>> points;
          in.get(points, "active set points");
          if (!std::all_of(
                  points.begin(), points.end(), [](const auto &p) { return finite_tensor(p); }))
            in.damaged("its active set holds points that are not finite");
          return [this, points]() { view.active_set = points; };
        });
    state_list.add(
        "accumulated slip",
        Scope::checkpoint_only,
        [this](StateWriter &out) { out.put(view.cumulative_slip.list()); },
        [this](StateReader &in) -> std::function<void()> {
          std::vector<double> slips;
          in.get(slips, "accumulated slip values");
          if (!valid_slips<dim>(slips))
            in.damaged("its accumulated slip is not a list of whole, finite entries");
          return [this, slips]() { view.cumulative_slip.restore(slips); };
        });
  }

  template <int dim>
  void
  Checkpoint<dim>::register_output_state()
  {
    RunState &state_list = view.state_list;
    state_list.add(
        "pvd records",
        Scope::checkpoint_only,
        [this](StateWriter &out) {
          const auto &records = view.solution_output.records();
          out.put(static_cast<std::uint64_t>(records.size()));
          for (const auto &[t, file] : records)
            {
              out.put(t);
              out.put(file);
            }
        },
        [this](StateReader &in) -> std::function<void()> {
          // (a record takes at least its time and its name's length)
          std::vector<std::pair<double, std::string>> records(
              in.count(".pvd records", 2 * sizeof(std::uint64_t)));
          for (auto &[t, record] : records)
            {
              in.get(t);
              in.get(record, 64, "a .pvd record");
              if (!std::isfinite(t) || !is_solution_record(record))
                in.damaged("a .pvd record is not a time and a file solution_<step>.pvtu");
            }
          return [this, records]() { view.solution_output.set_records(records); };
        });
    // the output files continue where the checkpoint was taken (after the .pvd records)
    state_list.add(
        "output files",
        Scope::checkpoint_only,
        [this](StateWriter &out) {
          out.put(view.statistics.state());
          out.put(cycles_log_bytes());
        },
        [this](StateReader &in) -> std::function<void()> {
          StatisticsWriter::State rows;
          unsigned long           cycles_bytes = 0;
          in.get(rows);
          in.get(cycles_bytes);
          return [this, rows, cycles_bytes]() { continue_outputs(cycles_bytes, rows); };
        });
  }

  // Explicit instantiation of the members defined in this file (ContactProblem
  // itself is instantiated once, in contact_problem.cc).
#define SL_INSTANTIATE(dim)                                                                \
  template typename Checkpoint<dim>::View ContactProblem<dim>::checkpoint_view();          \
  template void                           Checkpoint<dim>::register_run_state();           \
  template void                           Checkpoint<dim>::register_load_stepping_state(); \
  template void                           Checkpoint<dim>::register_field_state();         \
  template void                           Checkpoint<dim>::register_contact_state();       \
  template void                           Checkpoint<dim>::register_output_state();

  SL_INSTANTIATE(2)
  SL_INSTANTIATE(3)
#undef SL_INSTANTIATE
} // namespace StabilizedLagrangian
