#include <deal.II/base/bounding_box.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/distributed/grid_refinement.h>
#include <deal.II/distributed/solution_transfer.h>
#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/lac/affine_constraints.h>

#include <deal.II/numerics/error_estimator.h>
#include <deal.II/numerics/rtree.h>
#include <deal.II/numerics/vector_tools.h>

#include <stabilized_lagrangian/solver/mesh_refinement.h>

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>

namespace StabilizedLagrangian
{
  template <int dim>
  void
  MeshRefinement<dim>::refine()
  {
    flag_cells();
    // the mesh the flags make (with the smoothing's own flags), against the
    // memory of the machine: a refinement that cannot fit is not started
    Triangulation<dim> &triangulation = view.triangulation;
    triangulation.prepare_coarsening_and_refinement();
    unsigned int flagged = 0;
    for (const auto &cell : triangulation.active_cell_iterators())
      flagged += cell->is_locally_owned() && cell->refine_flag_set();
    const double cells = triangulation.n_global_active_cells();
    const double growth =
        (cells + Utilities::MPI::sum(flagged, view.communicator) * (std::pow(2., dim) - 1.)) /
        cells;
    check_memory_for_growth(growth);
    // the flags this rank set, so that a resumed run rebuilds the same mesh
    view.refinement_history.emplace_back();
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned() && cell->refine_flag_set())
        view.refinement_history.back().push_back(cell->id());
    execute();
  }

  template <int dim>
  void
  MeshRefinement<dim>::flag_cells()
  {
    using Criterion = Parameters::AdaptiveRefinement::Criterion;
    switch (view.parameters.criterion)
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
          const TrilinosWrappers::MPI::Vector u = view.ghosted_displacement();
          Vector<float>                       indicators(view.triangulation.n_active_cells());
          KellyErrorEstimator<dim>::estimate(view.displacement_dofs,
                                             QGauss<dim - 1>(view.displacement_degree + 1),
                                             {},
                                             u,
                                             indicators);
          mark_for_refinement(indicators);
          break;
        }
      case Criterion::estimator:
        // η_K of the last converged load step (ErrorEstimator)
        mark_for_refinement(view.error_indicators);
        break;
      }
    // η_K measures the energy error, spread over the body: the 30 % of the
    // cells it refines may hold none under Γc, where the pressure error is
    // (doc/error_estimator.md, "Accuracy targets")
    if (view.parameters.target_pressure_error > 0. &&
        (view.parameters.criterion == Criterion::kelly ||
         view.parameters.criterion == Criterion::estimator))
      flag_for_pressure();
  }

  template <int dim>
  void
  MeshRefinement<dim>::flag_for_pressure()
  {
    // bulk marking of the faces of Γc: the fewest cells whose squared
    // mismatch makes up pressure_bulk of its sum (Γc is a small part of the
    // mesh: every rank sorts all of it)
    constexpr double    pressure_bulk = 0.8;
    const Vector<float> indicators    = view.pressure_indicators();
    std::vector<float>  on_contact;
    for (const auto &cell : view.triangulation.active_cell_iterators())
      if (cell->is_locally_owned() && indicators[cell->active_cell_index()] > 0.f)
        on_contact.push_back(indicators[cell->active_cell_index()]);
    std::vector<float> all;
    for (const auto &part : Utilities::MPI::all_gather(view.communicator, on_contact))
      all.insert(all.end(), part.begin(), part.end());
    if (all.empty())
      return;
    std::sort(all.begin(), all.end(), std::greater<float>());
    double total = 0.;
    for (const float value : all)
      total += value;
    double carried   = 0.;
    float  threshold = all.back();
    for (const float value : all)
      {
        carried += value;
        threshold = value;
        if (carried >= pressure_bulk * total)
          break;
      }
    // with their face neighbours: the pressure is set by the stresses below Γc
    std::vector<typename Triangulation<dim>::active_cell_iterator> marked;
    for (const auto &cell : view.triangulation.active_cell_iterators())
      if (cell->is_locally_owned() && indicators[cell->active_cell_index()] >= threshold &&
          indicators[cell->active_cell_index()] > 0.f)
        marked.push_back(cell);
    for (const auto &cell : marked)
      {
        cell->clear_coarsen_flag();
        cell->set_refine_flag();
        for (const unsigned int f : cell->face_indices())
          if (!cell->at_boundary(f) && cell->neighbor(f)->is_active() &&
              cell->neighbor(f)->is_locally_owned())
            {
              cell->neighbor(f)->clear_coarsen_flag();
              cell->neighbor(f)->set_refine_flag();
            }
      }
  }

  template <int dim>
  void
  MeshRefinement<dim>::execute()
  {
    // the displacements of the earlier cycles follow the mesh (`Errors against
    // the last cycle`): the meshes are nested, so the interpolation is exact
    std::vector<TrilinosWrappers::MPI::Vector> &earlier_cycles = view.earlier_cycles;
    parallel::distributed::SolutionTransfer<dim, TrilinosWrappers::MPI::Vector> transfer(
        view.displacement_dofs);
    std::vector<const TrilinosWrappers::MPI::Vector *> carried;
    for (const auto &u : earlier_cycles)
      carried.push_back(&u);
    if (!carried.empty())
      transfer.prepare_for_coarsening_and_refinement(carried);
    view.triangulation.execute_coarsening_and_refinement();
    view.setup_after_refinement();
    if (carried.empty())
      return;
    std::vector<TrilinosWrappers::MPI::Vector> owned(
        carried.size(), TrilinosWrappers::MPI::Vector(view.locally_owned_u, view.communicator));
    std::vector<TrilinosWrappers::MPI::Vector *> targets;
    for (auto &u : owned)
      targets.push_back(&u);
    transfer.interpolate(targets);
    AffineConstraints<double> hanging_nodes(view.locally_relevant_u);
    DoFTools::make_hanging_node_constraints(view.displacement_dofs, hanging_nodes);
    hanging_nodes.close();
    for (unsigned int k = 0; k < owned.size(); ++k)
      {
        hanging_nodes.distribute(owned[k]);
        earlier_cycles[k].reinit(view.locally_owned_u, view.locally_relevant_u, view.communicator);
        earlier_cycles[k] = owned[k];
      }
  }

  template <int dim>
  void
  MeshRefinement<dim>::mark_for_refinement(const Vector<float> &indicators)
  {
    // adaptive refinement is refused on simplex meshes (check_cell_shape): the mesh is p4est's
    auto &p4est_mesh =
        dynamic_cast<parallel::distributed::Triangulation<dim> &>(view.triangulation);
    if (view.parameters.bulk_marking)
      parallel::distributed::GridRefinement::refine_and_coarsen_fixed_fraction(
          p4est_mesh, indicators, view.parameters.fraction, 0., VectorTools::L2_norm);
    else
      parallel::distributed::GridRefinement::refine_and_coarsen_fixed_number(
          p4est_mesh, indicators, view.parameters.fraction, 0.);
  }

  template <int dim>
  void
  MeshRefinement<dim>::flag_every_cell()
  {
    for (const auto &cell : view.triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        cell->set_refine_flag();
  }

  template <int dim>
  void
  MeshRefinement<dim>::check_memory_for_growth(const double growth) const
  {
    // The peak memory of this rank so far (the largest mesh yet, with its
    // factorisation) scaled by the growth of the mesh, to the power of the
    // direct solver's fill (about n log n in 2D, n^(4/3) in 3D; linear for the
    // iterative solver, whose multigrid hierarchy and Krylov basis grow with
    // the unknowns), against the physical memory shared by the ranks of this
    // node.
    Utilities::System::MemoryStats memory;
    Utilities::System::get_memory_stats(memory);
    const double fill = view.iterative_solver ? growth : std::pow(growth, dim == 3 ? 4. / 3. : 1.1);
    MPI_Comm     node;
    MPI_Comm_split_type(view.communicator, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
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
    const Utilities::System::MemoryStats &start = view.memory_at_start;
    double                                ratio = grown(memory.VmHWM, start.VmHWM) / physical;
    struct rlimit                         limit;
    if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
      ratio =
          std::max(ratio, grown(memory.VmPeak, start.VmPeak) / static_cast<double>(limit.rlim_cur));
    const double worst = Utilities::MPI::max(ratio, view.communicator);
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
  MeshRefinement<dim>::refine_around_active_set()
  {
    // every rank needs every active point: a cell may lie near another rank's
    std::vector<Point<dim>> points;
    for (const auto &part : Utilities::MPI::all_gather(view.communicator, view.active_set))
      points.insert(points.end(), part.begin(), part.end());
    if (points.empty())
      {
        view.pcout << "  no contact point was in contact: the mesh is refined globally\n";
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
    for (const auto &cell : view.triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const Point<dim> centre = cell->center();
          double           radius = 0.;
          for (const unsigned int v : cell->vertex_indices())
            radius = std::max(radius, centre.distance(cell->vertex(v)));
          std::vector<Point<dim>> nearest;
          tree.query(boost::geometry::index::nearest(centre, 1), std::back_inserter(nearest));
          if (centre.distance(nearest[0]) <=
              view.parameters.band * zone_size + radius * (1. + 1e-10))
            cell->set_refine_flag();
        }
  }

  template class MeshRefinement<2>;
  template class MeshRefinement<3>;
} // namespace StabilizedLagrangian
