#include <deal.II/base/mpi.h>

#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria_description.h>

#include <stabilized_lagrangian/solver/contact_problem.h>

#include <functional>
#include <optional>

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
      , triangulation_storage(new_triangulation(mpi_communicator, geometry->simplex_cells()))
      , triangulation(*triangulation_storage)
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
               axisymmetric}
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
    materials = Materials::create_all<dim>(prm);
    prm.enter_subsection("Contact");
    friction_law = FrictionLaws::create(prm, "Contact");
    prm.leave_subsection();
    for (const auto &name : sections.zones)
      {
        prm.enter_subsection("Contact");
        prm.enter_subsection("Zone " + name);
        const auto boundaries = Utilities::split_string_list(prm.get("Boundary ids"));
        if (!boundaries.empty())
          contact_zones.push_back(
              ContactZone{name, boundaries, FrictionLaws::create(prm, "Contact/Zone " + name)});
        prm.leave_subsection();
        prm.leave_subsection();
      }
    fe_pair = Discretization::Registry<dim>::create_without_parameters(contact_parameters.fe_pair);
    // the elements from the start: the boundary conditions' view
    // (boundary_view()) reads the displacement's before the first DoFs are set up
    fe_u                    = fe_pair->displacement_element();
    fe_m                    = fe_pair->multiplier_element(any_friction() ? dim : 1);
    multiplier_dofs_on_face = dofs_on_each_face(*fe_m);
    choose_complementarity();
    if (!contact_zones.empty() && weighted_complementarity())
      throw InputError("Contact/Zone " + contact_zones[0].name +
                       ": contact zones with their own friction law are built for the "
                       "pointwise conditions only; use Contact/Complementarity = pointwise.");
    pcout << LinearSolvers::set_threads(linear_solver_parameters.threads_per_rank) << "\n";

    std::ostringstream used;
    prm.print_parameters(used, ParameterHandler::PRM);
    parameters_used = used.str();
    register_run_state();
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
    loops.set_can_change(Loop::geometry, !(partner->is_flat() && !finite_strain()));
    loops.set_can_change(Loop::friction, any_friction() && any_pressure_dependent_threshold());
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
          E_max = std::max(E_max, material_of(cell).youngs_modulus());
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
            -> const Materials::Interface<dim> & { return material_of(cell); });
  }

  namespace
  {
    std::string
    list_ids(const std::set<types::boundary_id> &ids)
    {
      std::string result;
      for (const auto id : ids)
        result += (result.empty() ? "" : ", ") + std::to_string(id);
      return result;
    }
  } // namespace

  template <int dim>
  std::unique_ptr<parallel::DistributedTriangulationBase<dim>>
  ContactProblem<dim>::new_triangulation(const MPI_Comm &communicator, const bool simplex)
  {
    if (simplex)
      return std::make_unique<parallel::fullydistributed::Triangulation<dim>>(communicator);
    return std::make_unique<parallel::distributed::Triangulation<dim>>(
        communicator,
        typename Triangulation<dim>::MeshSmoothing(
            Triangulation<dim>::limit_level_difference_at_vertices));
  }

  template <int dim>
  void
  ContactProblem<dim>::distribute_simplex_mesh()
  {
    Triangulation<dim> serial;
    geometry->create_mesh(serial);
    serial.refine_global(extra_refinements);
    if (serial.has_hanging_nodes() && fe_pair->displacement_degree() > 1 &&
        Utilities::MPI::n_mpi_processes(mpi_communicator) > 1)
      throw InputError(
          "Geometry: a locally refined simplex mesh with the quadratic pair " +
          contact_parameters.fe_pair +
          " runs on one MPI rank only: deal.II 9.4 cannot constrain the hanging nodes of P2 "
          "next to another rank's cells. Use P1/P1, one rank, or uniform refinement only "
          "(Local refinements = 0).");
    // METIS is deterministic: the same ranks get the same cells in every run (restart)
    GridTools::partition_triangulation(Utilities::MPI::n_mpi_processes(mpi_communicator), serial);
    const auto description =
        TriangulationDescription::Utilities::create_description_from_triangulation(
            serial, mpi_communicator);
    triangulation.clear();
    for (const auto id : serial.get_manifold_ids())
      if (id != numbers::flat_manifold_id)
        triangulation.set_manifold(id, serial.get_manifold(id));
    triangulation.create_triangulation(description);
    // The faces between this rank's ghost layer and the cells it does not
    // hold are boundary faces of its local mesh, with the default id 0, a
    // user's id: move them to an id of their own, so that no boundary or
    // contact condition sees them.
    for (const auto &cell : triangulation.active_cell_iterators())
      for (const unsigned int f : cell->face_indices())
        if (cell->face(f)->at_boundary() &&
            !serial.create_cell_iterator(cell->id())->face(f)->at_boundary())
          cell->face(f)->set_boundary_id(ghost_layer_boundary_id);
  }

  template <int dim>
  void
  ContactProblem<dim>::refine_globally()
  {
    if (simplex_mesh())
      {
        ++extra_refinements;
        distribute_simplex_mesh();
      }
    else
      triangulation.refine_global(1);
  }

  template <int dim>
  void
  ContactProblem<dim>::check_cell_shape() const
  {
    const std::string pair = "Contact/Finite element pair = " + contact_parameters.fe_pair;
    if (fe_pair->simplex() && !simplex_mesh())
      throw InputError(pair + " is for triangles / tetrahedra; the mesh has " +
                       (dim == 2 ? "quadrilaterals" : "hexahedra") +
                       ": use a Q pair (Q1/P1, Q2/P1, Q2/P2, ...) or a simplex mesh "
                       "(Geometry/.../Cell shape = simplex, or a Gmsh mesh of " +
                       (dim == 2 ? "triangles)." : "tetrahedra)."));
    if (!fe_pair->simplex() && simplex_mesh())
      throw InputError(pair + " is for quadrilaterals / hexahedra; the mesh has " +
                       (dim == 2 ? "triangles" : "tetrahedra") +
                       ": use a P pair (P1/P1, P2/P1, P2/P2, or P1/P2 to see an unstable one).");
    if (fe_pair->dual_multiplier() && !weighted_complementarity())
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
      for (const auto &material : materials)
        if (material.modified_volume())
          throw InputError(material.slot +
                           "/Volumetric formulation: F-bar and mixed are built for plane strain "
                           "and 3D; an axisymmetric model (Geometry/Axisymmetric = true) uses "
                           "Volumetric formulation = displacement.");
    if (!simplex_mesh())
      return;
    for (const auto &material : materials)
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
  ContactProblem<dim>::share_ghost_boundary_ids()
  {
    using Ids = std::vector<types::boundary_id>;
    GridTools::exchange_cell_data_to_ghosts<Ids, Triangulation<dim>>(
        triangulation,
        [](const typename Triangulation<dim>::active_cell_iterator &cell) -> std::optional<Ids> {
          Ids ids;
          for (const auto &face : cell->face_iterators())
            ids.push_back(face->at_boundary() ? face->boundary_id() : numbers::invalid_boundary_id);
          return ids;
        },
        [](const typename Triangulation<dim>::active_cell_iterator &cell, const Ids &ids) {
          for (const unsigned int f : cell->face_indices())
            if (cell->face(f)->at_boundary())
              cell->face(f)->set_boundary_id(ids[f]);
        });
  }

  template <int dim>
  void
  ContactProblem<dim>::make_grid()
  {
    check_cell_shape();
    if (simplex_mesh())
      distribute_simplex_mesh();
    else
      {
        geometry->create_mesh(triangulation);
        share_ghost_boundary_ids();
      }
    resolve_boundaries();
    assign_material_slots();
    if (axisymmetric)
      {
        double smallest_radius = std::numeric_limits<double>::max(), size = 0.;
        for (const auto &cell : triangulation.active_cell_iterators())
          if (cell->is_locally_owned())
            for (const unsigned int v : cell->vertex_indices())
              {
                smallest_radius = std::min(smallest_radius, cell->vertex(v)[0]);
                size            = std::max(size, cell->diameter());
              }
        smallest_radius = Utilities::MPI::min(smallest_radius, mpi_communicator);
        size            = Utilities::MPI::max(size, mpi_communicator);
        if (smallest_radius < -1e-10 * size)
          {
            std::ostringstream message;
            message << "Geometry/Axisymmetric = true: the mesh reaches x = " << smallest_radius
                    << " mm, but x is the radius r >= 0 of the solid of revolution. Mesh only "
                       "the half x >= 0 of the section (Geometry/half ball/Symmetry planes = "
                       "true, or a Gmsh mesh of it).";
            throw InputError(message.str());
          }
      }
    for (const auto &condition : boundary_conditions)
      for (const auto id : condition->boundaries())
        require_boundary(id, condition->section() + "/Boundary id");
  }

  template <int dim>
  void
  ContactProblem<dim>::require_boundary(const types::boundary_id id, const std::string &entry) const
  {
    // (a rank of a fully distributed mesh sees only the boundaries near its cells)
    std::set<types::boundary_id> mesh_ids;
    for (const auto mesh_id : triangulation.get_boundary_ids())
      if (mesh_id != ghost_layer_boundary_id)
        mesh_ids.insert(mesh_id);
    mesh_ids = Utilities::MPI::compute_set_union(mesh_ids, mpi_communicator);
    if (mesh_ids.count(id) == 0)
      throw InputError(entry + " = " + std::to_string(id) +
                       ": the mesh has no boundary with this id; it has " + list_ids(mesh_ids) +
                       ".");
  }

  template <int dim>
  void
  ContactProblem<dim>::resolve_boundaries()
  {
    // boundaries given by name: the mesh's names (a Gmsh file's physical groups)
    const auto names   = geometry->boundary_names();
    const auto resolve = [&](const std::string &name, const std::string &entry) {
      const auto found = names.find(name);
      if (found != names.end())
        return found->second;
      std::string groups;
      for (const auto &[group, id] : names)
        groups +=
            (groups.empty() ? "" : ", ") + ("'" + group + "' (id " + std::to_string(id) + ")");
      std::string bodies;
      for (const auto &body : geometry->body_names())
        bodies += (bodies.empty() ? "" : ", ") + ("'" + body.first + "'");
      throw InputError(entry + " = '" + name + "': the mesh has no boundary of this name; " +
                       (names.empty() ? std::string("its boundaries have ids only")
                                      : "its boundaries are " + groups) +
                       (bodies.empty() ? "" : "; its bodies are " + bodies) + ".");
    };
    for (const auto &name : contact_parameters.boundary_names)
      chosen.contact_boundaries.insert(resolve(name, "Contact/Contact boundary ids"));
    for (const auto &name : contact_parameters.master_names)
      chosen.master_boundaries.insert(resolve(name, "Contact/Master boundary ids"));
    for (const auto &condition : boundary_conditions)
      condition->resolve_boundaries(resolve);

    for (const auto id : chosen.contact_boundaries)
      require_boundary(id, "Contact/Contact boundary ids");
    zone_of_boundary.clear();
    for (unsigned int z = 0; z < contact_zones.size(); ++z)
      for (const auto &entry : contact_zones[z].boundaries)
        {
          const std::string where = "Contact/Zone " + contact_zones[z].name + "/Boundary ids";
          const auto        id    = Parameters::boundary_id_or_name(entry, where);
          const types::boundary_id boundary = id ? *id : resolve(entry, where);
          if (chosen.contact_boundaries.count(boundary) == 0)
            throw InputError(where + ": boundary " + entry +
                             " is not a contact boundary (Contact/Contact boundary ids).");
          if (!zone_of_boundary.emplace(boundary, z + 1).second)
            throw InputError(where + ": boundary " + entry + " is already in another zone.");
        }
    for (const auto id : chosen.master_boundaries)
      {
        require_boundary(id, "Contact/Master boundary ids");
        if (chosen.contact_boundaries.count(id) > 0)
          throw InputError("Contact/Master boundary ids: boundary " + std::to_string(id) +
                           " is also in Contact/Contact boundary ids; the slave and master "
                           "surfaces must be different boundaries.");
      }
  }

  template <int dim>
  void
  ContactProblem<dim>::assign_material_slots()
  {
    // bodies of the material slots, by name (a Gmsh file's physical groups) or material id
    std::set<types::material_id> mesh_bodies;
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        mesh_bodies.insert(cell->material_id());
    {
      std::set<types::material_id>          all_bodies;
      const std::vector<types::material_id> local(mesh_bodies.begin(), mesh_bodies.end());
      for (const auto &part : Utilities::MPI::all_gather(mpi_communicator, local))
        all_bodies.insert(part.begin(), part.end());
      mesh_bodies = all_bodies;
    }
    const auto body_names = geometry->body_names();
    material_slots.clear();
    for (unsigned int slot = 1; slot < materials.size(); ++slot)
      for (const auto &body : materials[slot].bodies)
        {
          const std::string  entry = materials[slot].slot + "/Bodies";
          types::material_id id    = numbers::invalid_material_id;
          const auto         named = body_names.find(body);
          if (named != body_names.end())
            id = named->second;
          else if (!body.empty() && body.find_first_not_of("0123456789") == std::string::npos)
            id = static_cast<types::material_id>(std::stoul(body));
          if (id == numbers::invalid_material_id || mesh_bodies.count(id) == 0)
            {
              std::string known;
              for (const auto &[name, tag] : body_names)
                known += (known.empty() ? "" : ", ") +
                         ("'" + name + "' (id " + std::to_string(tag) + ")");
              for (const auto tag : mesh_bodies)
                known += (known.empty() ? "" : ", ") + ("id " + std::to_string(tag));
              throw InputError(entry + " = '" + body +
                               "': the mesh has no body of this name or "
                               "material id; its bodies are " +
                               known + ".");
            }
          if (material_slots.count(id) > 0)
            throw InputError(entry + " = '" + body + "': this body is already given the model of " +
                             materials[material_slots[id]].slot + ".");
          material_slots[id] = slot;
        }
  }

  template <int dim>
  bool
  ContactProblem<dim>::any_law(
      const std::function<bool(const FrictionLaws::Interface &)> &property) const
  {
    return property(*friction_law) ||
           std::any_of(contact_zones.begin(), contact_zones.end(), [&](const auto &zone) {
             return property(*zone.friction_law);
           });
  }

  template <int dim>
  bool
  ContactProblem<dim>::any_friction() const
  {
    return any_law([](const auto &law) { return law.has_friction(); });
  }

  template <int dim>
  bool
  ContactProblem<dim>::any_pressure_dependent_threshold() const
  {
    return any_law([](const auto &law) { return law.threshold_depends_on_pressure(); });
  }

  template class ContactProblem<2>;
  template class ContactProblem<3>;
} // namespace StabilizedLagrangian
