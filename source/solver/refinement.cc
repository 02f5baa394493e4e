#include <deal.II/base/bounding_box.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/lac/vector.h>

#include <deal.II/distributed/grid_refinement.h>
#include <deal.II/distributed/solution_transfer.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_values.h>

#include <deal.II/numerics/error_estimator.h>
#include <deal.II/numerics/vector_tools.h>
#include <deal.II/numerics/rtree.h>

#include <stabilized_lagrangian/contact/friction_law_check.h>
#include <stabilized_lagrangian/contact/stabilized_lagrangian.h>
#include <stabilized_lagrangian/postprocessing/safe_files.h>
#include <stabilized_lagrangian/solver/contact_problem.h>

#include <sys/resource.h>
#include <unistd.h>

#include <cmath>
#include <iomanip>
#include <optional>
#include <sstream>

namespace StabilizedLagrangian
{
  template <int dim>
  void
  ContactProblem<dim>::compute_contact_statistics(StepStatistics &stats)
  {
    double largest_displacement = 0.;
    for (const auto i : locally_owned_u)
      largest_displacement = std::max(largest_displacement, std::abs(solution(i)));
    // the multiplier equations of the converged iterate (system_rhs is its residual)
    Contact::FrictionLawCheck<dim> check(largest_displacement);
    for (const auto &[row, component] : owned_multiplier_components)
      if (multiplier_length_weights(row) > 0.)
        check.add_multiplier_row(component == 0,
                                 std::abs(system_rhs(row)) / multiplier_length_weights(row));
    conditions->statistics(stats, check, active_set);
    stats.friction_law_violations =
        check.gather(mpi_communicator, solver_parameters.friction_tolerance);
    stats.friction_law_report = check.report();
    compute_reactions(stats);
  }

  template <int dim>
  std::vector<types::boundary_id>
  ContactProblem<dim>::supported_boundaries() const
  {
    std::vector<types::boundary_id> ids;
    for (const auto &condition : boundary_conditions)
      condition->add_supported_boundaries(ids);
    return ids;
  }

  template <int dim>
  StatisticsWriter::Supports
  ContactProblem<dim>::statistics_supports() const
  {
    StatisticsWriter::Supports supports;
    supports.force_unit          = force_unit(true);
    supports.reaction_boundaries = supported_boundaries();
    for (const auto &condition : boundary_conditions)
      condition->add_statistics_columns(supports);
    for (const auto &zone : contact_zones)
      supports.zones.push_back(zone.name);
    return supports;
  }

  template <int dim>
  void
  ContactProblem<dim>::compute_reactions(StepStatistics &stats) const
  {
    const std::vector<types::boundary_id> ids = supported_boundaries();
    std::vector<Tensor<1, dim>>           reactions(ids.size());
    IndexSet                              claimed(dof_handler_u.n_dofs());
    // the Dirichlet conditions' residual on their DoFs (each once), the springs' force
    std::optional<TrilinosWrappers::MPI::Vector> u;
    const Quadrature<dim - 1> face_quadrature = face_gauss(fe_pair->displacement_degree() + 1);
    const BoundaryConditions::ReactionInputs<dim> inputs{
        internal_force,
        external_force,
        contact_residual,
        [&]() -> const TrilinosWrappers::MPI::Vector & {
          if (!u)
            u = ghosted_displacement();
          return *u;
        },
        face_quadrature};
    for (const auto &condition : boundary_conditions)
      condition->add_reactions(boundary_view(), inputs, ids, reactions, claimed);
    stats.reactions.assign(ids.size(), {{0., 0., 0.}});
    for (unsigned int b = 0; b < ids.size(); ++b)
      {
        const Tensor<1, dim> total = Utilities::MPI::sum(reactions[b], mpi_communicator);
        for (unsigned int d = 0; d < dim; ++d)
          stats.reactions[b][d] = total[d];
      }
    stats.point_reactions.clear();
    stats.condition_values.clear();
    for (const auto &condition : boundary_conditions)
      condition->add_statistics(boundary_view(), inputs, stats);
  }

  template <int dim>
  TrilinosWrappers::MPI::Vector
  ContactProblem<dim>::ghosted_displacement() const
  {
    TrilinosWrappers::MPI::Vector u_owned(locally_owned_u, mpi_communicator);
    for (const auto index : locally_owned_u)
      u_owned(index) = solution(index);
    u_owned.compress(VectorOperation::insert);
    TrilinosWrappers::MPI::Vector u(locally_owned_u, locally_relevant_u, mpi_communicator);
    u = u_owned;
    return u;
  }

  template <int dim>
  void
  ContactProblem<dim>::mark_for_refinement(const Vector<float> &indicators)
  {
    // adaptive refinement is refused on simplex meshes (check_cell_shape): the mesh is p4est's
    auto &p4est_mesh = dynamic_cast<parallel::distributed::Triangulation<dim> &>(triangulation);
    if (adaptive_refinement.bulk_marking)
      parallel::distributed::GridRefinement::refine_and_coarsen_fixed_fraction(
          p4est_mesh, indicators, adaptive_refinement.fraction, 0., VectorTools::L2_norm);
    else
      parallel::distributed::GridRefinement::refine_and_coarsen_fixed_number(
          p4est_mesh, indicators, adaptive_refinement.fraction, 0.);
  }

  template <int dim>
  void
  ContactProblem<dim>::refine_mesh()
  {
    using Criterion = Parameters::AdaptiveRefinement::Criterion;
    switch (adaptive_refinement.criterion)
      {
      case Criterion::active_set:
        refine_around_active_set();
        break;
      case Criterion::uniform:
        flag_every_cell();
        break;
      case Criterion::kelly:
        {
          // Kelly indicators of the displacement of the last converged state
          const TrilinosWrappers::MPI::Vector u = ghosted_displacement();
          Vector<float>                       indicators(triangulation.n_active_cells());
          KellyErrorEstimator<dim>::estimate(dof_handler_u,
                                             QGauss<dim - 1>(fe_pair->displacement_degree() + 1),
                                             {},
                                             u,
                                             indicators);
          mark_for_refinement(indicators);
          break;
        }
      case Criterion::estimator:
        // η_K of the last converged load step (estimate_error())
        mark_for_refinement(error_indicators);
        break;
      }
    // the mesh the flags make (with the smoothing's own flags), against the
    // memory of the machine: a refinement that cannot fit is not started
    triangulation.prepare_coarsening_and_refinement();
    unsigned int flagged = 0;
    for (const auto &cell : triangulation.active_cell_iterators())
      flagged += cell->is_locally_owned() && cell->refine_flag_set();
    const double cells = triangulation.n_global_active_cells();
    const double growth =
        (cells + Utilities::MPI::sum(flagged, mpi_communicator) * (std::pow(2., dim) - 1.)) / cells;
    check_memory_for_growth(growth);
    // the flags this rank set, so that a resumed run rebuilds the same mesh
    refinement_history.emplace_back();
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned() && cell->refine_flag_set())
        refinement_history.back().push_back(cell->id());
    // the displacements of the earlier cycles follow the mesh (`Errors against
    // the last cycle`): the meshes are nested, so the interpolation is exact
    parallel::distributed::SolutionTransfer<dim, TrilinosWrappers::MPI::Vector> transfer(
        dof_handler_u);
    std::vector<const TrilinosWrappers::MPI::Vector *> carried;
    for (const auto &u : earlier_cycles)
      carried.push_back(&u);
    if (!carried.empty())
      transfer.prepare_for_coarsening_and_refinement(carried);
    triangulation.execute_coarsening_and_refinement();
    setup_after_refinement();
    if (carried.empty())
      return;
    std::vector<TrilinosWrappers::MPI::Vector> owned(
        carried.size(), TrilinosWrappers::MPI::Vector(locally_owned_u, mpi_communicator));
    std::vector<TrilinosWrappers::MPI::Vector *> targets;
    for (auto &u : owned)
      targets.push_back(&u);
    transfer.interpolate(targets);
    AffineConstraints<double> hanging_nodes(locally_relevant_u);
    DoFTools::make_hanging_node_constraints(dof_handler_u, hanging_nodes);
    hanging_nodes.close();
    for (unsigned int k = 0; k < owned.size(); ++k)
      {
        hanging_nodes.distribute(owned[k]);
        earlier_cycles[k].reinit(locally_owned_u, locally_relevant_u, mpi_communicator);
        earlier_cycles[k] = owned[k];
      }
  }

  template <int dim>
  void
  ContactProblem<dim>::flag_every_cell()
  {
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        cell->set_refine_flag();
  }

  template <int dim>
  void
  ContactProblem<dim>::write_cycle_errors(const std::string &directory) const
  {
    // ‖u_N − u_k‖ in the energy norm of the tangent of the last state
    // (for a linear material, the energy norm itself)
    FEValues<dim>                    fe_values(*fe_u,
                            cell_quadrature,
                            update_values | update_gradients | update_quadrature_points |
                                update_JxW_values);
    const FEValuesExtractors::Vector displacement(0);
    const unsigned int               n_q = cell_quadrature.size();
    std::vector<Tensor<2, dim>>      last(n_q), earlier(n_q);
    std::vector<Tensor<1, dim>>      last_u(n_q), earlier_u(n_q); // axisymmetric: hoop strains
    std::vector<double>              squared(earlier_cycles.size(), 0.);
    compute_volume_fields(earlier_cycles.back());
    for (const auto &cell : dof_handler_u.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values[displacement].get_function_gradients(earlier_cycles.back(), last);
          fe_values[displacement].get_function_values(earlier_cycles.back(), last_u);
          std::vector<Materials::Response<dim>> tangents(n_q);
          for (unsigned int q = 0; q < n_q; ++q)
            tangents[q] =
                committed_response(cell,
                                   q,
                                   cell_quadrature.point(q),
                                   last[q],
                                   nullptr,
                                   hoop_strain(fe_values.quadrature_point(q), last_u[q], last[q]));
          for (unsigned int k = 0; k + 1 < earlier_cycles.size(); ++k)
            {
              fe_values[displacement].get_function_gradients(earlier_cycles[k], earlier);
              fe_values[displacement].get_function_values(earlier_cycles[k], earlier_u);
              for (unsigned int q = 0; q < n_q; ++q)
                {
                  const Point<dim>    &x     = fe_values.quadrature_point(q);
                  const Tensor<2, dim> error = last[q] - earlier[q];
                  const double         hoop =
                      hoop_strain(x, last_u[q] - earlier_u[q], last[q] - earlier[q]);
                  const auto &A = tangents[q];
                  squared[k] +=
                      (scalar_product(error, double_contract<2, 0, 3, 1>(A.tangent, error)) +
                       hoop * (scalar_product(A.hoop_row + A.hoop_column, error) +
                               A.hoop_hoop * hoop)) *
                      fe_values.JxW(q) * radial_weight(x);
                }
            }
        }
    Utilities::MPI::sum(squared, mpi_communicator, squared);
    if (Utilities::MPI::this_mpi_process(mpi_communicator) != 0)
      return;
    std::ostringstream file;
    file << "cycle,displacement_dofs,estimated_error_sqrtNmm,error_against_last_cycle_sqrtNmm,"
            "effectivity_index\n";
    for (unsigned int k = 0; k + 1 < earlier_cycles.size(); ++k)
      {
        const double error = std::sqrt(std::max(squared[k], 0.));
        file << k << ',' << cycle_records[k].first << ',' << std::setprecision(8)
             << cycle_records[k].second << ',' << error << ','
             << (error > 0. ? cycle_records[k].second / error : 0.) << '\n';
      }
    SafeFiles::write_atomically(directory + "/cycle_errors.csv", file.str());
  }

  template <int dim>
  void
  ContactProblem<dim>::check_memory_for_growth(const double growth) const
  {
    // The peak memory of this rank so far (the largest mesh yet, with its
    // factorisation) scaled by the growth of the mesh, to the power of the
    // direct solver's fill (about n log n in 2D, n^(4/3) in 3D; linear for the
    // iterative solver, whose multigrid hierarchy and Krylov basis grow with
    // the unknowns), against the physical memory shared by the ranks of this
    // node.
    Utilities::System::MemoryStats memory;
    Utilities::System::get_memory_stats(memory);
    const double fill = iterative_solver ? growth : std::pow(growth, dim == 3 ? 4. / 3. : 1.1);
    MPI_Comm     node;
    MPI_Comm_split_type(mpi_communicator, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
    const unsigned int ranks_on_node = Utilities::MPI::n_mpi_processes(node);
    MPI_Comm_free(&node);
    const double physical = static_cast<double>(sysconf(_SC_PHYS_PAGES)) *
                            static_cast<double>(sysconf(_SC_PAGESIZE)) / ranks_on_node;
    // resident memory against the physical memory, and the address space
    // against its limit where one is set (ulimit -v, a batch system's)
    // (what the process held before the mesh existed, its libraries, does not grow)
    const auto grown = [&](const double peak_kb, const double start_kb) {
      return 1024. * (start_kb + std::max(peak_kb - start_kb, 0.) * fill);
    };
    double        ratio = grown(memory.VmHWM, memory_at_start.VmHWM) / physical;
    struct rlimit limit;
    if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
      ratio = std::max(ratio,
                       grown(memory.VmPeak, memory_at_start.VmPeak) /
                           static_cast<double>(limit.rlim_cur));
    const double worst = Utilities::MPI::max(ratio, mpi_communicator);
    if (worst > 0.9)
      throw std::runtime_error(
          "Adaptive refinement: the next refinement cycle multiplies the cells by " +
          std::to_string(growth) + " and would need about " +
          std::to_string(static_cast<long>(worst * 100.)) +
          " % of the memory each rank has (estimated from its peak so far). Stopping "
          "before it; the results of the cycles done are kept. Use fewer `Adaptive "
          "refinement/Cycles`, a smaller `Refined fraction`, or more machines.");
  }

  template <int dim>
  void
  ContactProblem<dim>::refine_around_active_set()
  {
    // every rank needs every active point: a cell may lie near another rank's
    std::vector<Point<dim>> points;
    for (const auto &part : Utilities::MPI::all_gather(mpi_communicator, active_set))
      points.insert(points.end(), part.begin(), part.end());
    if (points.empty())
      {
        pcout << "  no contact point was in contact: the mesh is refined globally\n";
        flag_every_cell();
        return;
      }
    // the band scales with the size of the active zone (its bounding box's
    // diameter), so the material below the contact, where the stresses vary
    // over that size, is refined too; the cell's radius about its centre
    // keeps the cells that contain or touch active points. A contact that
    // starts at a single point (a zone of size 0) sits on a vertex, exactly
    // one radius from each cell around it: the tolerance keeps those cells.
    const auto   box = BoundingBox<dim>(points);
    const double zone_size =
        box.get_boundary_points().first.distance(box.get_boundary_points().second);
    const auto tree = pack_rtree(points);
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const Point<dim> centre = cell->center();
          double           radius = 0.;
          for (const unsigned int v : cell->vertex_indices())
            radius = std::max(radius, centre.distance(cell->vertex(v)));
          std::vector<Point<dim>> nearest;
          tree.query(boost::geometry::index::nearest(centre, 1), std::back_inserter(nearest));
          if (centre.distance(nearest[0]) <=
              adaptive_refinement.band * zone_size + radius * (1. + 1e-10))
            cell->set_refine_flag();
        }
  }

  // Explicit instantiation of the members defined in this file (the class
  // itself is instantiated once, in contact_problem.cc).
#define SL_INSTANTIATE(dim)                                                                          \
  template void ContactProblem<dim>::compute_contact_statistics(StepStatistics &);                   \
  template std::vector<types::boundary_id> ContactProblem<dim>::supported_boundaries() const;        \
  template void ContactProblem<dim>::compute_reactions(StepStatistics &) const;                      \
  template StatisticsWriter::Supports    ContactProblem<dim>::statistics_supports() const;           \
  template TrilinosWrappers::MPI::Vector ContactProblem<dim>::ghosted_displacement() const;          \
  template void                          ContactProblem<dim>::refine_mesh();                         \
  template void                          ContactProblem<dim>::check_memory_for_growth(double) const; \
  template void                          ContactProblem<dim>::refine_around_active_set();            \
  template void                          ContactProblem<dim>::flag_every_cell();                     \
  template void ContactProblem<dim>::mark_for_refinement(const Vector<float> &);                     \
  template void ContactProblem<dim>::write_cycle_errors(const std::string &) const;

  SL_INSTANTIATE(2)
  SL_INSTANTIATE(3)
#undef SL_INSTANTIATE
} // namespace StabilizedLagrangian
