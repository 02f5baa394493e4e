#include <deal.II/base/mpi.h>

#include <deal.II/grid/grid_tools.h>

#include <stabilized_lagrangian/postprocessing/safe_files.h>
#include <stabilized_lagrangian/solver/contact_problem.h>

#include <functional>

#include <cmath>
#include <limits>
#include <sstream>

namespace StabilizedLagrangian
{
  namespace
  {
    /** The struct of a parameter subsection, parsed once. */
    template <typename Section, typename... Arguments>
    Section
    parsed(ParameterHandler &prm, const Arguments &...arguments)
    {
      Section section;
      section.parse_parameters(prm, arguments...);
      return section;
    }

    /** `Geometry/Axisymmetric`, refused outside 2D. */
    template <int dim>
    bool
    parsed_axisymmetric(ParameterHandler &prm)
    {
      prm.enter_subsection("Geometry");
      const bool axisymmetric = prm.get_bool("Axisymmetric");
      prm.leave_subsection();
      if (axisymmetric && dim != 2)
        throw InputError("Geometry/Axisymmetric = true needs Dimension = 2 (the meridian "
                         "section of the solid of revolution).");
      return axisymmetric;
    }

    /** The obstacle's prescribed motion, `Obstacle/Motion`, as parsed. */
    template <int dim> struct ParsedObstacleMotion
    {
      std::shared_ptr<Parameters::BoundaryFunction<dim>> translation;
      /** null for an angle of 0 (the default): no rotation */
      std::shared_ptr<Parameters::BoundaryFunction<dim>> rotation;
      Point<dim>                                         rotation_centre;
    };

    /** Parse `Obstacle/Motion`: the translation, the rotation and its centre. */
    template <int dim>
    ParsedObstacleMotion<dim>
    parsed_obstacle_motion(ParameterHandler &prm)
    {
      ParsedObstacleMotion<dim> motion;
      prm.enter_subsection("Obstacle");
      motion.translation = Parameters::parse_function<dim>(prm, "Obstacle", "Motion");
      prm.enter_subsection("Motion");
      const std::vector<double> centre =
          Utilities::string_to_double(Utilities::split_string_list(prm.get("Rotation centre")));
      for (unsigned int d = 0; d < dim; ++d)
        motion.rotation_centre[d] = centre[d];
      // an angle of 0 (the default) is no rotation: a plane's pairing then
      // follows the obstacle within the step (Contact::RigidObstacle::is_flat())
      prm.enter_subsection("Rotation");
      bool turns = false;
      for (const auto &component :
           Utilities::split_string_list(prm.get("Function expression"), ';'))
        turns |= component != "0";
      prm.leave_subsection();
      if (turns)
        motion.rotation =
            Parameters::parse_function<dim>(prm, "Obstacle/Motion", "Rotation", dim == 2 ? 1 : 3);
      prm.leave_subsection();
      prm.leave_subsection();
      return motion;
    }

    /**
     * Per face number, the DoFs of @p fe on that face, ascending (the face's
     * own DoFs: FE_SimplexP's has_support_on_face() says true for all).
     */
    template <int dim>
    std::vector<std::vector<unsigned int>>
    dofs_on_each_face(const FiniteElement<dim> &fe)
    {
      std::vector<std::vector<unsigned int>> result(fe.reference_cell().n_faces());
      for (unsigned int face = 0; face < result.size(); ++face)
        {
          for (unsigned int j = 0; j < fe.n_dofs_per_face(face); ++j)
            result[face].push_back(fe.face_to_cell_index(j, face));
          std::sort(result[face].begin(), result[face].end());
        }
      return result;
    }
  } // namespace

  template <int dim>
  ContactProblem<dim>::ContactProblem(ParameterHandler                    &prm,
                                      const Parameters::ConditionSections &sections,
                                      const bool                           verbose)
      : mpi_communicator(MPI_COMM_WORLD)
      , pcout(std::cout, verbose && Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      , timer(pcout, TimerOutput::never, TimerOutput::wall_times)
      , geometry(Geometry::create<dim>(prm))
      , axisymmetric(parsed_axisymmetric<dim>(prm))
      , contact_parameters(parsed<Parameters::Contact>(prm))
      , boundary_conditions(BoundaryConditions::create<dim>(prm, sections))
      , load_stepping(parsed<Parameters::LoadStepping>(prm))
      , solver_parameters(parsed<Parameters::NonlinearSolver>(prm))
      , linear_solver_parameters(parsed<Parameters::LinearSolver>(prm))
      , output_parameters(parsed<Parameters::Output>(prm))
      , adaptive_refinement(parsed<Parameters::AdaptiveRefinement>(prm))
      , chosen(contact_parameters)
      , output_directory(output_parameters.directory)
      , body_mesh(mpi_communicator, *geometry, contact_parameters.fe_pair)
      , triangulation(body_mesh.triangulation())
      , dof_handler_u(triangulation)
      , dof_handler_m(triangulation)
      , verbose(verbose)
      , spaces{fe_u,
               fe_m,
               dof_handler_m,
               multiplier_dofs_on_face,
               n_u,
               n_multipliers,
               step_start,
               axisymmetric,
               chosen.contact_boundaries,
               chosen.master_boundaries}
      , solution_output(mpi_communicator, output_parameters)
  {
    Utilities::System::get_memory_stats(memory_at_start);
    loops = LoopPolicy(solver_parameters);

    obstacle                               = Obstacles::create<dim>(prm);
    const ParsedObstacleMotion<dim> motion = parsed_obstacle_motion<dim>(prm);
    obstacle_translation                   = motion.translation;
    obstacle_rotation                      = motion.rotation;
    obstacle_motion                        = std::make_shared<const Contact::ObstacleMotion<dim>>(
        obstacle_translation, obstacle_rotation, motion.rotation_centre);
    body_response.set_slots(Materials::create_all<dim>(prm));
    contact_zones = Contact::FrictionZones(prm, sections.zones);
    fe_pair = Discretization::Registry<dim>::create_without_parameters(contact_parameters.fe_pair);
    // the elements from the start: the boundary conditions' view
    // (boundary_view()) reads the displacement's before the first DoFs are set up
    fe_u                    = fe_pair->displacement_element();
    fe_m                    = fe_pair->multiplier_element(contact_zones.any_friction() ? dim : 1);
    multiplier_dofs_on_face = dofs_on_each_face(*fe_m);
    geometry->set_size_check(std::make_shared<const Geometry::SizeCheck>(
        Geometry::SizeCheck::Run{dim,
                                 fe_pair->displacement_degree(),
                                 Geometry::SizeCheck::refinement_entry(prm),
                                 linear_solver_parameters,
                                 load_stepping.n_steps,
                                 mpi_communicator,
                                 &pcout}));
    contact.choose_complementarity();
    pcout << LinearSolvers::set_threads(linear_solver_parameters.threads_per_rank) << "\n";

    std::ostringstream used;
    prm.print_parameters(used, ParameterHandler::PRM);
    parameters_used = used.str();
    checkpoint.register_run_state();
  }

  template <int dim>
  bool
  ContactProblem<dim>::run(const bool resume)
  {
    const bool root = Utilities::MPI::this_mpi_process(mpi_communicator) == 0;
    run_directory   = output_parameters.directory;
    // nothing is written before the input is known to be good: the mesh and
    // the boundary names are checked by setup()
    setup();
    if (!resume)
      solution_output.prepare_directory(output_directory);
    const unsigned int first_cycle = resume ? checkpoint.restore() : 0;
    // the estimate of the restored (converged) state, which the cycle's row
    // and the summary report if the checkpoint ended the cycle's load path
    if (resume)
      estimate_error(last_step);
    if (root)
      SafeFiles::write_atomically(run_directory + "/parameters.prm", parameters_used);
    // the load path on each mesh of the adaptive refinement cycles
    return refinement_cycles.run(first_cycle, resume);
  }

  template <int dim>
  void
  ContactProblem<dim>::setup()
  {
    TimerOutput::Scope scope(timer, "setup");
    make_grid();
    setup_after_refinement();
    if (partner->is_rigid())
      {
        // the bodies' bounding box over all ranks
        const auto box = GridTools::compute_bounding_box(triangulation);
        Point<dim> middle;
        for (unsigned int d = 0; d < dim; ++d)
          middle[d] =
              0.5 * (Utilities::MPI::min(box.get_boundary_points().first[d], mpi_communicator) +
                     Utilities::MPI::max(box.get_boundary_points().second[d], mpi_communicator));
        obstacle_motion->check_centre(middle, GridTools::diameter(triangulation));
      }
    // a flat obstacle in small strain never moves the pairing; a frictionless
    // or Tresca law never moves the threshold
    loops.set_pairing(partner->has_pairing_derivatives(), partner->is_flat());
    loops.set_can_change(Loop::geometry, !(partner->is_flat() && !body_response.finite_strain()));
    loops.set_can_change(Loop::friction,
                         contact_zones.any_friction() &&
                             contact_zones.any_pressure_dependent_threshold());
    SceneChecks<dim>(scene_view()).warn_before_run();
  }

  namespace
  {
    /**
     * The contact pressure, as a fraction of the largest Young's modulus, below
     * which the friction threshold sees zero. A point that was open at the
     * previous Newton iterate gets λ_n = 0 up to round-off (about 1e-16 of the
     * largest pressure), and if it closes, s = μ λ_n > 0 or not — friction
     * active (χ_f = 1, with the coupling ∂T/∂λ_n = −μ P_B(ĝ)) or not — would be
     * decided by the rounding, that is by the BLAS kernel and thread count.
     */
    constexpr double negligible_pressure_fraction = 1e-12;

    /**
     * The gap, as a fraction of the body's diameter, below which a point
     * touches for the contact status: coordinates carry round-off of about
     * 1e-16 of the body's size, so a vertex meant to rest on the obstacle sits
     * within 1e-14 of it or so.
     */
    constexpr double touching_gap_fraction = 1e-12;
  } // namespace

  template <int dim>
  void
  ContactProblem<dim>::setup_after_refinement()
  {
    SceneChecks<dim>(scene_view()).choose_augmentation_parameters(chosen);
    double E_max = 0., h_min = std::numeric_limits<double>::max();
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          E_max = std::max(E_max, body_response.material_of(cell).youngs_modulus());
          h_min = std::min(h_min, cell->minimum_vertex_distance());
        }
    E_max               = Utilities::MPI::max(E_max, mpi_communicator);
    nodal_stiffness     = E_max * std::pow(Utilities::MPI::min(h_min, mpi_communicator), dim - 2.);
    negligible_pressure = negligible_pressure_fraction * E_max;
    touching_gap        = touching_gap_fraction * GridTools::diameter(triangulation);
    bounds.set_body_diameter(GridTools::diameter(triangulation));
    setup_dofs();
    free_rigid_motions = SceneChecks<dim>(scene_view()).rigid_motions_left_free();
    setup_contact_points();
    material_history.initialize(
        triangulation,
        cell_quadrature.size(),
        [this](const typename Triangulation<dim>::active_cell_iterator &cell)
            -> const Materials::Interface<dim> & { return body_response.material_of(cell); });
  }

  template <int dim>
  void
  ContactProblem<dim>::check_cell_shape() const
  {
    const std::string pair = "Contact/Finite element pair = " + contact_parameters.fe_pair;
    if (fe_pair->simplex() && !body_mesh.simplex())
      throw InputError(pair + " is for triangles / tetrahedra; the mesh has " +
                       (dim == 2 ? "quadrilaterals" : "hexahedra") +
                       ": use a Q pair (Q1/P1, Q2/P1, Q2/P2, ...) or a simplex mesh "
                       "(Geometry/.../Cell shape = simplex, or a Gmsh mesh of " +
                       (dim == 2 ? "triangles)." : "tetrahedra)."));
    if (!fe_pair->simplex() && body_mesh.simplex())
      throw InputError(pair + " is for quadrilaterals / hexahedra; the mesh has " +
                       (dim == 2 ? "triangles" : "tetrahedra") +
                       ": use a P pair (P1/P1, P2/P1, P2/P2, or P1/P2 to see an unstable one).");
    if (fe_pair->dual_multiplier() && !chosen.weighted_complementarity())
      throw InputError(pair +
                       " has dual multipliers, whose conditions hold node by node: set "
                       "Contact/Complementarity = weighted, or choose the pair without 'dual'.");
    if (fe_pair->dual_multiplier() &&
        contact_parameters.quadrature == Parameters::ContactQuadrature::gauss_lobatto)
      throw InputError(pair +
                       " and Contact/Contact quadrature = Gauss-Lobatto: the dual basis "
                       "is biorthogonal under exact integration, while the nodal quadrature "
                       "lumps the multiplier mass (the standard basis is then its own dual). "
                       "Use Contact quadrature = Gauss, or the pair without 'dual'.");
    if (axisymmetric && fe_pair->displacement_degree() > 1 &&
        contact_parameters.quadrature == Parameters::ContactQuadrature::gauss_lobatto)
      throw InputError(pair + " with Contact/Contact quadrature = Gauss-Lobatto in an axisymmetric "
                              "model: the nodal weight of a quadratic face's node on the axis, the "
                              "integral of its shape function times 2 pi r, is zero, so its "
                              "multiplier would be undetermined. Use Contact quadrature = Gauss.");
    if (axisymmetric)
      for (const auto &material : body_response.slots())
        if (material.modified_volume())
          throw InputError(material.slot +
                           "/Volumetric formulation: F-bar and mixed are built for plane strain "
                           "and 3D; an axisymmetric model (Geometry/Axisymmetric = true) uses "
                           "Volumetric formulation = displacement.");
    if (!body_mesh.simplex())
      return;
    for (const auto &material : body_response.slots())
      if (material.volumetric == Materials::BodyMaterial<dim>::Volumetric::mixed &&
          fe_pair->displacement_degree() == 1)
        throw InputError(material.slot + "/Volumetric formulation = mixed: " + pair +
                         " has linear displacements, whose volume change is already one per "
                         "cell, so a cell-wise pressure adds nothing and the body locks. Use "
                         "P2/P1 or P2/P2 (P2 displacements with a P0 pressure, inf-sup stable).");
    if (adaptive_refinement.cycles > 0)
      throw InputError("Adaptive refinement/Cycles must be 0 on a simplex mesh: its "
                       "distributed triangulation (deal.II 9.4's fully distributed one; p4est "
                       "holds only hypercubes) cannot be refined in place. Refine the mesh "
                       "uniformly with Geometry/.../Global refinements.");
    // (two bodies of tetrahedra: Contact::MasterSurface refuses its triangle
    // faces, once the master boundary's names are resolved)
  }

  template <int dim>
  void
  ContactProblem<dim>::make_grid()
  {
    check_cell_shape();
    body_mesh.create(fe_pair->displacement_degree());
    // the boundaries given by name: the mesh's ids (a Gmsh file's physical
    // groups); then the contact boundaries, zones and master checked
    const auto resolve = [&](const std::string &name, const std::string &entry) {
      return body_mesh.boundary_named(name, entry);
    };
    for (const auto &name : contact_parameters.boundary_names)
      chosen.contact_boundaries.insert(resolve(name, "Contact/Contact boundary ids"));
    for (const auto &name : contact_parameters.master_names)
      chosen.master_boundaries.insert(resolve(name, "Contact/Master boundary ids"));
    for (const auto &condition : boundary_conditions)
      condition->resolve_boundaries(resolve);
    for (const auto id : chosen.contact_boundaries)
      body_mesh.require_boundary(id, "Contact/Contact boundary ids");
    contact_zones.resolve(resolve, chosen.contact_boundaries);
    for (const auto id : chosen.master_boundaries)
      {
        body_mesh.require_boundary(id, "Contact/Master boundary ids");
        if (chosen.contact_boundaries.count(id) > 0)
          throw InputError("Contact/Master boundary ids: boundary " + std::to_string(id) +
                           " is also in Contact/Contact boundary ids; the slave and master "
                           "surfaces must be different boundaries.");
      }
    body_mesh.assign_material_slots(body_response.slots());
    if (axisymmetric)
      body_mesh.check_meridian_section();
    for (const auto &condition : boundary_conditions)
      for (const auto id : condition->boundaries())
        body_mesh.require_boundary(id, condition->section() + "/Boundary id");
  }

  template class ContactProblem<2>;
  template class ContactProblem<3>;
} // namespace StabilizedLagrangian
