#include <deal.II/base/bounding_box.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_system.h>

#include <deal.II/grid/grid_tools.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/vector.h>

#include <deal.II/distributed/grid_refinement.h>

#include <deal.II/numerics/error_estimator.h>
#include <deal.II/numerics/rtree.h>
#include <deal.II/numerics/vector_tools.h>

#include <stabilized_lagrangian/contact/friction_law_check.h>
#include <stabilized_lagrangian/contact/stabilized_lagrangian.h>
#include <stabilized_lagrangian/solver/contact_problem.h>

#include <sys/resource.h>
#include <unistd.h>

#include <cmath>
#include <limits>
#include <sstream>

namespace StabilizedLagrangian
{
  template <int dim>
  ContactProblem<dim>::ContactProblem(ParameterHandler &prm, const bool verbose)
      : mpi_communicator(MPI_COMM_WORLD)
      , pcout(std::cout, verbose && Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      , timer(pcout, TimerOutput::never, TimerOutput::wall_times)
      , triangulation(mpi_communicator,
                      typename Triangulation<dim>::MeshSmoothing(
                          Triangulation<dim>::limit_level_difference_at_vertices))
      , dof_handler_u(triangulation)
      , dof_handler_m(triangulation)
      , verbose(verbose)
  {
    Utilities::System::get_memory_stats(memory_at_start);
    contact_parameters.parse_parameters(prm);
    boundary_conditions.parse_parameters(prm);
    load_stepping.parse_parameters(prm);
    solver_parameters.parse_parameters(prm);
    linear_solver_parameters.parse_parameters(prm);
    output_parameters.parse_parameters(prm);
    adaptive_refinement.parse_parameters(prm);

    geometry  = Geometry::create<dim>(prm);
    obstacle  = Obstacles::create<dim>(prm);
    materials = Materials::create_all<dim>(prm);
    prm.enter_subsection("Contact");
    friction_law = FrictionLaws::create(prm);
    prm.leave_subsection();
    fe_pair = Discretization::Registry<dim>::create_without_parameters(contact_parameters.fe_pair);
    pcout << LinearSolvers::set_threads(linear_solver_parameters.threads_per_rank) << "\n";

    std::ostringstream used;
    prm.print_parameters(used, ParameterHandler::PRM);
    parameters_used = used.str();
  }

  template <int dim>
  void
  ContactProblem<dim>::setup()
  {
    TimerOutput::Scope scope(timer, "setup");
    make_grid();
    setup_after_refinement();
    warn_if_body_behind_obstacle();
    warn_if_pair_locks();
    warn_if_dirichlet_not_ramped();
  }

  template <int dim>
  std::string
  ContactProblem<dim>::rigid_motions_left_free() const
  {
    // The rigid motions (dim translations, then the rotations about the
    // body's centre, scaled by its size) restricted to the prescribed
    // components of the Dirichlet vertices: G = Σ m mᵀ over those (vertex,
    // component) pairs; the eigenvectors of G with a zero eigenvalue are the
    // motions no Dirichlet condition holds.
    if (master_surface)
      return ""; // two bodies: each is held by the other or by its conditions
    const unsigned int n_rotations = dim == 2 ? 1 : 3;
    const unsigned int n_modes     = dim + n_rotations;
    const auto         box         = GridTools::compute_bounding_box(triangulation);
    const Point<dim>   centre      = box.center();
    double             size        = 0.;
    for (unsigned int d = 0; d < dim; ++d)
      size = std::max(size, box.side_length(d));
    FullMatrix<double> gram(n_modes, n_modes);
    Vector<double>     m(n_modes);
    for (const auto &bc : boundary_conditions.dirichlet)
      for_each_dirichlet_vertex(bc, [&](const Point<dim> &vertex) {
        for (unsigned int d = 0; d < dim; ++d)
          if (bc.components[d])
            {
              const Tensor<1, dim> x = (vertex - centre) / size;
              m                      = 0.;
              m[d]                   = 1.;
              // component d of the rotations ω × x (2D: about z)
              if (dim == 2)
                m[dim] = d == 0 ? -x[1] : x[0];
              else
                for (unsigned int axis = 0; axis < 3; ++axis)
                  {
                    Tensor<1, 3> w, xx;
                    w[axis] = 1.;
                    for (unsigned int i = 0; i < dim; ++i)
                      xx[i] = x[i];
                    m[dim + axis] = cross_product_3d(w, xx)[d];
                  }
              for (unsigned int i = 0; i < n_modes; ++i)
                for (unsigned int j = 0; j < n_modes; ++j)
                  gram(i, j) += m[i] * m[j];
            }
      });
    Utilities::MPI::sum(gram, mpi_communicator, gram);
    double trace = 0.;
    for (unsigned int i = 0; i < n_modes; ++i)
      trace += gram(i, i);
    LAPACKFullMatrix<double> matrix(n_modes);
    matrix = gram;
    Vector<double>     eigenvalues;
    FullMatrix<double> eigenvectors;
    matrix.compute_eigenvalues_symmetric(-1., 1e-10 * trace, 0., eigenvalues, eigenvectors);
    std::string free;
    const char *axes = "xyz";
    for (unsigned int k = 0; k < eigenvalues.size(); ++k)
      {
        double rotation = 0.;
        for (unsigned int i = dim; i < n_modes; ++i)
          rotation += eigenvectors(i, k) * eigenvectors(i, k);
        std::ostringstream motion;
        if (rotation < 1e-6)
          {
            motion << "the translation along";
            for (unsigned int i = 0; i < dim; ++i)
              if (std::abs(eigenvectors(i, k)) > 1e-3)
                motion << ' ' << (eigenvectors(i, k) < 0 ? "-" : "") << axes[i];
          }
        else
          motion << "a rotation";
        free += (free.empty() ? "" : ", ") + motion.str();
      }
    return free;
  }

  template <int dim>
  unsigned int
  ContactProblem<dim>::points_in_contact() const
  {
    unsigned int count = 0;
    for (const auto &state : contact_states)
      count += state.in_contact;
    return Utilities::MPI::sum(count, mpi_communicator);
  }

  template <int dim>
  void
  ContactProblem<dim>::close_nearest_points()
  {
    // Nothing touches and the Dirichlet conditions leave a rigid motion free:
    // the loads alone cannot bring the body onto the obstacle in a
    // quasi-static step (its system is singular). It is put on the obstacle
    // by its points nearest to it, as a body lowered until it touches.
    double nearest = std::numeric_limits<double>::max();
    for_each_contact_point([&](ContactPointState<dim> &state, const ContactKinematics<dim> &k) {
      nearest = std::min(nearest, state.pairing.gap(k.position));
    });
    nearest = Utilities::MPI::min(nearest, mpi_communicator);
    for_each_contact_point([&](ContactPointState<dim> &state, const ContactKinematics<dim> &k) {
      state.in_contact = state.pairing.gap(k.position) <= nearest + touching_gap;
    });
    pcout << "  nothing touches the obstacle and the Dirichlet conditions leave "
          << free_rigid_motions << " free: the " << points_in_contact()
          << " contact point(s) nearest to it (gap " << nearest << " mm) start in contact\n";
  }

  template <int dim>
  void
  ContactProblem<dim>::warn_if_pair_locks() const
  {
    // Volumetric locking: with a bulk modulus far above the shear modulus,
    // K/G = 2(1 + ν)/(3(1 − 2ν)), low-order displacements cannot deform at
    // constant volume and the body answers far too stiffly (a block of
    // ν = 0.4999 pressed on a plane with Q1/P1: 3.6 times the normal force of
    // Q2/P2). Q1 locks from K/G ≈ 50 (ν ≈ 0.49), Q2 much later.
    const double limit = fe_pair->displacement_degree() == 1 ? 0.49 : 0.4999;
    for (const auto &material : materials)
      {
        const double nu = material.model->poissons_ratio();
        if (nu < limit)
          continue;
        pcout << "WARNING: " << material.slot << ": Poisson's ratio " << nu << " (bulk modulus "
              << 2. * (1. + nu) / (3. * (1. - 2. * nu))
              << " times the shear modulus) with displacements of degree "
              << fe_pair->displacement_degree()
              << " (Contact/Finite element pair = " << contact_parameters.fe_pair
              << "): the body locks volumetrically, its displacements and forces are far too "
                 "stiff. Use quadratic displacements (Q2/P1, Q2/P2), which lock much later; no "
                 "formulation here is locking-free yet.\n";
      }
  }

  template <int dim>
  void
  ContactProblem<dim>::warn_if_body_behind_obstacle() const
  {
    if (master_surface)
      return;
    // most of the body on the wrong side of the surface: the obstacle's normal
    // points into the body (g_n = (x − x̄)·n < 0 means penetration)
    const double tolerance = 1e-8 * GridTools::diameter(triangulation);
    unsigned int behind = 0, vertices = 0;
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int v : cell->vertex_indices())
          {
            ++vertices;
            behind += obstacle->project(cell->vertex(v)).gap(cell->vertex(v)) < -tolerance;
          }
    behind   = Utilities::MPI::sum(behind, mpi_communicator);
    vertices = Utilities::MPI::sum(vertices, mpi_communicator);
    if (2 * behind > vertices)
      pcout << "WARNING: " << behind << " of " << vertices
            << " cell vertices lie behind the obstacle's surface (negative gap) before the first "
               "step. The obstacle's normal must point out of the obstacle, towards the body: "
               "check the `Obstacle` entries (a plane's Normal, for instance).\n";
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
    choose_augmentation_parameters();
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
    free_rigid_motions  = rigid_motions_left_free();
    touching_gap        = touching_gap_fraction * GridTools::diameter(triangulation);
    setup_dofs();
    setup_contact_points();
    material_history.initialize(
        triangulation,
        cell_quadrature.size(),
        [this](const typename Triangulation<dim>::active_cell_iterator &cell)
            -> const Materials::Interface<dim> & { return material_of(cell); });
  }

  namespace
  {
    /**
     * Multilinear weights of the vertices of a face at vertex @p v of its
     * child @p c (isotropic refinement, children and vertices numbered
     * lexicographically); empty when that vertex is a vertex of the face.
     */
    template <int dim>
    std::vector<double>
    child_vertex_weights(const unsigned int c, const unsigned int v)
    {
      std::array<double, dim - 1> xi;
      bool                        face_vertex = true;
      for (unsigned int d = 0; d < dim - 1; ++d)
        {
          xi[d] = 0.5 * (((c >> d) & 1) + ((v >> d) & 1));
          face_vertex &= (xi[d] == 0. || xi[d] == 1.);
        }
      if (face_vertex)
        return {};
      std::vector<double> weights(GeometryInfo<dim>::vertices_per_face, 1.);
      for (unsigned int k = 0; k < weights.size(); ++k)
        for (unsigned int d = 0; d < dim - 1; ++d)
          weights[k] *= ((k >> d) & 1) ? xi[d] : 1. - xi[d];
      return weights;
    }

    /**
     * The floor of the force scale of the scaled Newton criterion, as a fraction
     * of the force E h^(dim−2) U that displaces a node of a cell by the largest
     * displacement U: the residual's round-off is about 1e-16–1e-14 of that
     * force, so with the default tolerance 1e-8 the criterion stays two orders
     * above round-off even when the body does not deform.
     */
    constexpr double force_scale_floor = 1e-4;

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
  void
  ContactProblem<dim>::make_grid()
  {
    geometry->create_mesh(triangulation);

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
      contact_parameters.boundary_ids.insert(resolve(name, "Contact/Contact boundary ids"));
    for (const auto &name : contact_parameters.master_names)
      contact_parameters.master_ids.insert(resolve(name, "Contact/Master boundary ids"));
    for (auto &bc : boundary_conditions.dirichlet)
      if (!bc.boundary_name.empty())
        bc.boundary_id = resolve(bc.boundary_name, "Boundary conditions/Dirichlet/Boundary id");
    for (auto &bc : boundary_conditions.neumann)
      if (!bc.boundary_name.empty())
        bc.boundary_id = resolve(bc.boundary_name, "Boundary conditions/Neumann/Boundary id");

    std::set<types::boundary_id> mesh_ids;
    for (const auto id : triangulation.get_boundary_ids())
      mesh_ids.insert(id);
    const auto require = [&](const types::boundary_id id, const std::string &entry) {
      if (mesh_ids.count(id) == 0)
        throw InputError(entry + " = " + std::to_string(id) +
                         ": the mesh has no boundary with this id; it has " + list_ids(mesh_ids) +
                         ".");
    };
    for (const auto id : contact_parameters.boundary_ids)
      require(id, "Contact/Contact boundary ids");
    for (const auto id : contact_parameters.master_ids)
      {
        require(id, "Contact/Master boundary ids");
        if (contact_parameters.boundary_ids.count(id) > 0)
          throw InputError("Contact/Master boundary ids: boundary " + std::to_string(id) +
                           " is also in Contact/Contact boundary ids; the slave and master "
                           "surfaces must be different boundaries.");
      }

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
    for (const auto &bc : boundary_conditions.dirichlet)
      require(bc.boundary_id, "Boundary conditions/Dirichlet/Boundary id");
    for (const auto &bc : boundary_conditions.neumann)
      require(bc.boundary_id, "Boundary conditions/Neumann/Boundary id");
  }

  template <int dim>
  void
  ContactProblem<dim>::choose_augmentation_parameters()
  {
    if (!contact_parameters.r_n_automatic && !contact_parameters.r_t_automatic)
      return;
    double h = 0.;
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int f : cell->face_indices())
          if (is_contact_face(cell, f))
            h = std::max(h, cell->face(f)->diameter());
    h = Utilities::MPI::max(h, mpi_communicator);
    AssertThrow(h > 0., ExcMessage("the contact boundary has no faces"));
    // E of the softest body at the contact (slave or master): with a rigid
    // obstacle the slave's; with two bodies the softer one's, because there the
    // solution depends on r_n (doc/formulation.md, two deformable bodies) and the
    // rigid limit of a stiffening master must keep the slave's r_n
    double E = std::numeric_limits<double>::max();
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary() &&
              (contact_parameters.boundary_ids.count(cell->face(f)->boundary_id()) > 0 ||
               contact_parameters.master_ids.count(cell->face(f)->boundary_id()) > 0))
            E = std::min(E, material_of(cell).youngs_modulus());
    E = Utilities::MPI::min(E, mpi_communicator);
    if (contact_parameters.r_n_automatic)
      {
        contact_parameters.r_n =
            contact_parameters.r_n_factor * Contact::automatic_r_n_constant * E / h;
        pcout << "  r_n = automatic: " << contact_parameters.r_n_factor << " x "
              << Contact::automatic_r_n_constant << " E/h = " << contact_parameters.r_n
              << " N/mm^3 (E = " << E << " MPa, h = " << h << " mm)\n";
      }
    if (contact_parameters.r_t_automatic)
      {
        // without prescribed motion, the contact mesh size is the length scale
        const double increment = largest_dirichlet_increment();
        const double length    = increment > 0. ? increment : h;
        contact_parameters.r_t =
            contact_parameters.r_t_factor * Contact::automatic_r_t_constant / length;
        pcout << "  r_t = automatic: " << contact_parameters.r_t_factor << " x "
              << Contact::automatic_r_t_constant << "/l = " << contact_parameters.r_t
              << " 1/mm (l = " << length << " mm, "
              << (increment > 0. ? "the largest prescribed displacement increment of a load step"
                                 : "h: no prescribed displacement increment")
              << ")\n";
      }
  }

  template <int dim>
  double
  ContactProblem<dim>::largest_dirichlet_increment()
  {
    // The body starts undeformed (u = 0), so the first step's increment is
    // the value at the end of that step, whatever the function gives at t = 0.
    const double   step      = load_stepping.end_time / load_stepping.n_steps;
    double         increment = 0.;
    Vector<double> before(dim), after(dim);
    for (const auto &bc : boundary_conditions.dirichlet)
      for_each_dirichlet_vertex(bc, [&](const Point<dim> &vertex) {
        for (unsigned int k = 0; k < load_stepping.n_steps; ++k)
          {
            before = 0.;
            if (k > 0)
              {
                bc.displacement->set_time(k * step);
                bc.displacement->vector_value(vertex, before);
              }
            bc.displacement->set_time((k + 1) * step);
            bc.displacement->vector_value(vertex, after);
            double norm_squared = 0.;
            for (unsigned int d = 0; d < dim; ++d)
              if (bc.components[d])
                norm_squared += Utilities::fixed_power<2>(after[d] - before[d]);
            increment = std::max(increment, std::sqrt(norm_squared));
          }
      });
    for (const auto &bc : boundary_conditions.dirichlet)
      bc.displacement->check_finite(mpi_communicator);
    return Utilities::MPI::max(increment, mpi_communicator);
  }

  template <int dim>
  void
  ContactProblem<dim>::warn_if_dirichlet_not_ramped() const
  {
    // A prescribed displacement that is not zero at t = 0 is applied whole in
    // the first load step, and cutting that step does not make it smaller.
    Vector<double> value(dim);
    for (const auto &bc : boundary_conditions.dirichlet)
      {
        double largest = 0.;
        bc.displacement->set_time(0.);
        for_each_dirichlet_vertex(bc, [&](const Point<dim> &vertex) {
          // (not noted as a failure: the run never evaluates t = 0)
          bc.displacement->Functions::ParsedFunction<dim>::vector_value(vertex, value);
          for (unsigned int d = 0; d < dim; ++d)
            if (bc.components[d] && std::isfinite(value[d]))
              largest = std::max(largest, std::abs(value[d]));
        });
        largest = Utilities::MPI::max(largest, mpi_communicator);
        if (largest > 0.)
          pcout << "WARNING: " << bc.displacement->name()
                << ": the prescribed displacement is not zero at t = 0 (up to " << largest
                << " mm); the body starts undeformed, so the first load step applies it at "
                   "once, and cutting that step does not reduce it. Make it grow from zero "
                   "with t (e.g. multiply it by t / End time) to spread it over the steps.\n";
      }
  }

  template <int dim>
  void
  ContactProblem<dim>::setup_dofs()
  {
    fe_u = fe_pair->displacement_element();
    fe_m = fe_pair->multiplier_element(friction_law->has_friction() ? dim : 1);
    dof_handler_u.distribute_dofs(*fe_u);
    dof_handler_m.distribute_dofs(*fe_m);
    setup_multiplier_numbering();

    n_u             = dof_handler_u.n_dofs();
    locally_owned_u = dof_handler_u.locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(dof_handler_u, locally_relevant_u);

    IndexSet contact_block(dof_handler_m.n_dofs());
    contact_block.add_range(0, n_multipliers);
    IndexSet relevant_m;
    DoFTools::extract_locally_relevant_dofs(dof_handler_m, relevant_m);
    const IndexSet owned_multipliers    = dof_handler_m.locally_owned_dofs() & contact_block;
    const IndexSet relevant_multipliers = relevant_m & contact_block;

    locally_owned.clear();
    locally_owned.set_size(n_u + n_multipliers);
    locally_owned.add_indices(locally_owned_u);
    locally_owned.add_indices(owned_multipliers, n_u);
    locally_owned.compress();
    locally_relevant.clear();
    locally_relevant.set_size(n_u + n_multipliers);
    locally_relevant.add_indices(locally_relevant_u);
    locally_relevant.add_indices(relevant_multipliers, n_u);
    master_surface.reset();
    if (!contact_parameters.master_ids.empty())
      {
        // every rank sees the whole master surface (its DoFs are ghosts)
        master_surface = std::make_unique<Contact::MasterSurface<dim>>(
            dof_handler_u, contact_parameters.master_ids, mpi_communicator);
        if (master_surface->n_faces() == 0)
          throw InputError("Contact/Master boundary ids: the master boundary has no faces.");
        locally_relevant.add_indices(master_surface->dofs());
      }
    locally_relevant.compress();

    const unsigned int u_degree = fe_pair->displacement_degree();
    cell_quadrature             = QGauss<dim>(u_degree + 1);
    if (contact_parameters.quadrature == Parameters::ContactQuadrature::gauss)
      contact_quadrature = QGauss<dim - 1>(std::max(u_degree, fe_pair->multiplier_degree()) + 1);
    else
      // nodal for the multiplier when it is at least as rich as the displacement
      // trace; otherwise enough points to integrate ψ φ·n exactly
      contact_quadrature =
          QGaussLobatto<dim - 1>(std::max({fe_pair->multiplier_degree(), u_degree, 1u}) + 1);

    hanging_constraints.clear();
    hanging_constraints.reinit(locally_relevant);
    DoFTools::make_hanging_node_constraints(dof_handler_u, hanging_constraints);
    add_multiplier_hanging_node_constraints(hanging_constraints);
    if (fe_pair->multiplier_on_coarser_mesh())
      add_multiplier_coarsening_constraints(hanging_constraints);
    // in 3D, chains of hanging nodes may end on another rank's DoFs
    hanging_constraints.make_consistent_in_parallel(
        locally_owned, locally_relevant, mpi_communicator);
    hanging_constraints.close();
    newton_constraints.clear();
    newton_constraints.reinit(locally_relevant);
    newton_constraints.merge(hanging_constraints);
    add_homogeneous_dirichlet_constraints(newton_constraints);
    add_prescribed_slip_constraints(newton_constraints);
    newton_constraints.make_consistent_in_parallel(
        locally_owned, locally_relevant, mpi_communicator);
    newton_constraints.close();

    system_rhs.reinit(locally_owned, mpi_communicator);
    solution.reinit(locally_owned, mpi_communicator);
    ghosted_solution.reinit(locally_owned, locally_relevant, mpi_communicator);
    step_start.reinit(locally_owned, locally_relevant, mpi_communicator);
    internal_force.reinit(locally_owned, mpi_communicator);
    external_force.reinit(locally_owned, mpi_communicator);
    multiplier_length_weights.reinit(locally_owned, mpi_communicator);
    owned_multiplier_components = locally_owned_multiplier_components();
    residual_scaling.reinit(locally_owned, mpi_communicator);
    residual_scaling = 1.;
    for (const auto &[row, component] : owned_multiplier_components)
      residual_scaling(row) = (component == 0) ? contact_parameters.r_n : contact_parameters.r_t;
    residual_scaling.compress(VectorOperation::insert);
  }

  template <int dim>
  void
  ContactProblem<dim>::add_multiplier_hanging_node_constraints(
      AffineConstraints<double> &constraints) const
  {
    // Continuity of the multipliers at the hanging vertices (and edges) of Γc
    // in 3D: the constraints of the trace element on the whole skeleton,
    // restricted to the Γc block and shifted to the monolithic numbering. The
    // skeleton's other DoFs are never used.
    IndexSet relevant_m;
    DoFTools::extract_locally_relevant_dofs(dof_handler_m, relevant_m);
    AffineConstraints<double> skeleton(relevant_m);
    DoFTools::make_hanging_node_constraints(dof_handler_m, skeleton);
    skeleton.close();
    for (const auto &line : skeleton.get_lines())
      {
        if (line.index >= n_multipliers)
          continue;
        // the contact boundary must not end inside a refined face: there a
        // hanging vertex of Γc depends on one off it, which has no multiplier
        AssertThrow(std::all_of(line.entries.begin(),
                                line.entries.end(),
                                [&](const auto &entry) { return entry.first < n_multipliers; }),
                    ExcMessage("Contact/Contact boundary ids: the contact boundary ends inside a "
                               "refined face (some children of the face are on it, some not), "
                               "so a multiplier at a hanging vertex would depend on one off the "
                               "contact boundary. Give all the children of a refined face the "
                               "same boundary id."));
        constraints.add_line(n_u + line.index);
        for (const auto &[column, weight] : line.entries)
          constraints.add_entry(n_u + line.index, n_u + column, weight);
      }
  }

  template <int dim>
  void
  ContactProblem<dim>::add_multiplier_coarsening_constraints(
      AffineConstraints<double> &constraints) const
  {
    // The multiplier is continuous and multilinear on the parent of each
    // contact face: the values at the vertices of the children that are not
    // vertices of the parent are interpolated from the parent's vertices.
    for (const auto &line : constraints.get_lines())
      if (line.index >= n_u)
        throw InputError("Contact/Finite element pair = " + contact_parameters.fe_pair +
                         " needs a contact boundary without hanging nodes.");
    constexpr unsigned int n_face_vertices = GeometryInfo<dim>::vertices_per_face;
    const unsigned int     n_components    = fe_m->n_components();
    for (const auto &cell : dof_handler_m.active_cell_iterators())
      if (!cell->is_artificial())
        for (const unsigned int f : cell->face_indices())
          if (is_contact_face(cell, f))
            {
              if (cell->level() == 0)
                throw InputError("Contact/Finite element pair = " + contact_parameters.fe_pair +
                                 " needs the contact boundary refined at least once.");
              const auto coarse_face = cell->parent()->face(f);
              for (unsigned int c = 0; c < coarse_face->n_children(); ++c)
                for (unsigned int v = 0; v < n_face_vertices; ++v)
                  {
                    const std::vector<double> weights = child_vertex_weights<dim>(c, v);
                    for (unsigned int component = 0; component < n_components && !weights.empty();
                         ++component)
                      {
                        const types::global_dof_index fine =
                            coarse_face->child(c)->vertex_dof_index(v, component);
                        std::vector<types::global_dof_index> coarse(n_face_vertices);
                        for (unsigned int k = 0; k < n_face_vertices; ++k)
                          coarse[k] = coarse_face->vertex_dof_index(k, component);
                        // at the edge of Γc a parent face may be only partly in
                        // Γc: its fine nodes there stay free
                        if (fine >= n_multipliers || constraints.is_constrained(n_u + fine) ||
                            *std::max_element(coarse.begin(), coarse.end()) >= n_multipliers)
                          continue;
                        constraints.add_line(n_u + fine);
                        for (unsigned int k = 0; k < n_face_vertices; ++k)
                          if (weights[k] != 0.)
                            constraints.add_entry(n_u + fine, n_u + coarse[k], weights[k]);
                      }
                  }
            }
  }

  template <int dim>
  void
  ContactProblem<dim>::add_homogeneous_dirichlet_constraints(
      AffineConstraints<double> &constraints) const
  {
    for (const auto &bc : boundary_conditions.dirichlet)
      VectorTools::interpolate_boundary_values(dof_handler_u,
                                               bc.boundary_id,
                                               Functions::ZeroFunction<dim>(dim),
                                               constraints,
                                               bc.components);
  }

  template <int dim>
  void
  ContactProblem<dim>::add_prescribed_slip_constraints(AffineConstraints<double> &constraints) const
  {
    if (!friction_law->has_friction() || master_surface || !obstacle->is_flat())
      return;
    const auto tangents = obstacle->project(Point<dim>()).tangents;
    // the vertex DoFs of the multiplier element by component (0: λ_n, 1..: Λ)
    std::vector<unsigned int> m_component(fe_m->n_dofs_per_vertex());
    for (unsigned int i = 0; i < m_component.size(); ++i)
      m_component[i] = fe_m->system_to_component_index(i).first;
    for (const auto &cell : dof_handler_u.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int f : cell->face_indices())
          if (is_contact_face(cell, f))
            {
              const auto face   = cell->face(f);
              const auto face_m = multiplier_cell(cell)->face(f);
              for (const unsigned int v : face->vertex_indices())
                for (unsigned int a = 0; a < dim - 1; ++a)
                  {
                    // t_α·u is prescribed when every component it involves is
                    bool prescribed = true;
                    for (unsigned int d = 0; d < dim; ++d)
                      if (std::abs(tangents[a][d]) > 1e-12)
                        {
                          const auto u = face->vertex_dof_index(v, d);
                          prescribed &= constraints.is_constrained(u) &&
                                        !hanging_constraints.is_constrained(u);
                        }
                    if (!prescribed)
                      continue;
                    for (unsigned int i = 0; i < m_component.size(); ++i)
                      if (m_component[i] == a + 1)
                        {
                          const auto m = n_u + face_m->vertex_dof_index(v, i);
                          if (!constraints.is_constrained(m))
                            constraints.add_line(m);
                        }
                  }
            }
  }

  template <int dim>
  void
  ContactProblem<dim>::setup_multiplier_numbering()
  {
    // Number the multiplier DoFs on Γc first, [0, N_Γ), rank after rank; the
    // others (on the rest of the skeleton) are never used.
    std::set<types::global_dof_index>    on_contact;
    std::vector<types::global_dof_index> dofs(fe_m->n_dofs_per_cell());
    for (const auto &cell : dof_handler_m.active_cell_iterators())
      if (!cell->is_artificial())
        for (const unsigned int f : cell->face_indices())
          if (is_contact_face(cell, f))
            {
              cell->get_dof_indices(dofs);
              for (unsigned int i = 0; i < dofs.size(); ++i)
                if (fe_m->has_support_on_face(i, f))
                  on_contact.insert(dofs[i]);
            }

    const IndexSet          owned           = dof_handler_m.locally_owned_dofs();
    types::global_dof_index n_contact_local = 0;
    for (const auto dof : on_contact)
      if (owned.is_element(dof))
        ++n_contact_local;
    const types::global_dof_index n_other_local = owned.n_elements() - n_contact_local;

    types::global_dof_index                 contact_offset = 0, other_offset = 0;
    const std::array<unsigned long long, 2> local  = {{n_contact_local, n_other_local}};
    std::array<unsigned long long, 2>       prefix = {{0, 0}};
    MPI_Exscan(local.data(), prefix.data(), 2, MPI_UNSIGNED_LONG_LONG, MPI_SUM, mpi_communicator);
    if (Utilities::MPI::this_mpi_process(mpi_communicator) > 0)
      {
        contact_offset = prefix[0];
        other_offset   = prefix[1];
      }
    n_multipliers = Utilities::MPI::sum(n_contact_local, mpi_communicator);

    std::vector<types::global_dof_index> new_numbers(owned.n_elements());
    types::global_dof_index              next_contact = contact_offset;
    types::global_dof_index              next_other   = n_multipliers + other_offset;
    for (unsigned int k = 0; k < owned.n_elements(); ++k)
      new_numbers[k] = on_contact.count(owned.nth_index_in_set(k)) ? next_contact++ : next_other++;
    dof_handler_m.renumber_dofs(new_numbers);
  }

  template <int dim>
  std::vector<std::pair<types::global_dof_index, unsigned int>>
  ContactProblem<dim>::locally_owned_multiplier_components() const
  {
    std::map<types::global_dof_index, unsigned int> components;
    std::vector<types::global_dof_index>            dofs(fe_m->n_dofs_per_cell());
    for (const auto &cell : dof_handler_m.active_cell_iterators())
      if (!cell->is_artificial())
        for (const unsigned int f : cell->face_indices())
          if (is_contact_face(cell, f))
            {
              cell->get_dof_indices(dofs);
              for (unsigned int i = 0; i < dofs.size(); ++i)
                if (fe_m->has_support_on_face(i, f) && locally_owned.is_element(n_u + dofs[i]))
                  components[n_u + dofs[i]] = fe_m->system_to_component_index(i).first;
            }
    return {components.begin(), components.end()};
  }

  template <int dim>
  void
  ContactProblem<dim>::setup_contact_points()
  {
    contact_faces.clear();
    unsigned int n_points = 0;
    for (const auto &cell : dof_handler_u.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int f : cell->face_indices())
          if (is_contact_face(cell, f))
            {
              contact_faces.push_back(ContactFace{cell, f, n_points, nullptr});
              n_points += contact_quadrature.size();
            }
    contact_states.assign(n_points, ContactPointState<dim>());
    if (!friction_law->threshold_depends_on_pressure())
      for (auto &state : contact_states)
        state.friction_threshold = friction_law->threshold(0.);

    // initial statuses from the initial configuration: touching points are in contact
    sparsity_ready = false;
    update_pairings(true);
    setup_sparsity();
    update_statuses();
    if (!free_rigid_motions.empty() && points_in_contact() == 0)
      close_nearest_points();
  }

  template <int dim>
  void
  ContactProblem<dim>::setup_sparsity()
  {
    TimerOutput::Scope                   scope(timer, "sparsity pattern");
    DynamicSparsityPattern               dsp(locally_relevant);
    std::vector<types::global_dof_index> u_dofs(fe_u->n_dofs_per_cell());
    for (const auto &cell : dof_handler_u.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          cell->get_dof_indices(u_dofs);
          newton_constraints.add_entries_local_to_global(u_dofs, dsp, false);
        }
    FaceEvaluator evaluator(*this, contact_quadrature);
    sparsity_master_faces.assign(contact_faces.size(), {});
    for (unsigned int c = 0; c < contact_faces.size(); ++c)
      {
        const ContactFace &face = contact_faces[c];
        evaluator.reinit(face, ghosted_solution);
        std::vector<types::global_dof_index> local_dofs = evaluator.u_dofs;
        local_dofs.insert(local_dofs.end(), evaluator.m_dofs.begin(), evaluator.m_dofs.end());
        if (master_surface)
          {
            // the paired master faces and their neighbours
            std::set<unsigned int> near;
            for (unsigned int q = 0; q < evaluator.n_points(); ++q)
              for (const unsigned int m : master_surface->neighbours(
                       contact_states[face.first_point + q].pairing.master_face))
                near.insert(m);
            sparsity_master_faces[c].assign(near.begin(), near.end());
            for (const unsigned int m : near)
              {
                const auto master_dofs = master_surface->face_dof_indices(m);
                local_dofs.insert(local_dofs.end(), master_dofs.begin(), master_dofs.end());
              }
            std::sort(local_dofs.begin(), local_dofs.end());
            local_dofs.erase(std::unique(local_dofs.begin(), local_dofs.end()), local_dofs.end());
          }
        newton_constraints.add_entries_local_to_global(local_dofs, dsp, false);
      }
    SparsityTools::distribute_sparsity_pattern(
        dsp, locally_owned, mpi_communicator, locally_relevant);
    // the factorisation refers to the old matrix: release it first
    direct_solver.reset();
    system_matrix.reinit(locally_owned, locally_owned, dsp, mpi_communicator);
    direct_solver =
        std::make_unique<LinearSolvers::DirectSolver>(linear_solver_parameters.direct_solver,
                                                      linear_solver_parameters.null_pivot_detection,
                                                      linear_solver_parameters.workspace_increase);
    sparsity_ready = true;
  }

  template <int dim>
  bool
  ContactProblem<dim>::pairings_left_sparsity() const
  {
    int left = 0;
    if (master_surface)
      {
        if (sparsity_master_faces.size() != contact_faces.size())
          left = 1;
        else
          for (unsigned int c = 0; c < contact_faces.size() && left == 0; ++c)
            for (unsigned int q = 0; q < face_quadrature(contact_faces[c]).size(); ++q)
              {
                const auto &faces = sparsity_master_faces[c];
                const int m = contact_states[contact_faces[c].first_point + q].pairing.master_face;
                if (!std::binary_search(faces.begin(), faces.end(), static_cast<unsigned int>(m)))
                  left = 1;
              }
      }
    return Utilities::MPI::max(left, mpi_communicator) == 1;
  }

  template <int dim>
  Obstacles::Pairing<dim>
  ContactProblem<dim>::pair(const Point<dim> &x) const
  {
    return master_surface ? master_surface->project(x) : obstacle->project(x);
  }

  template <int dim>
  void
  ContactProblem<dim>::follow_master(Obstacles::Pairing<dim> &pairing,
                                     ContactKinematics<dim>  &k) const
  {
    if (pairing.master_face < 0)
      return;
    const unsigned int    face = pairing.master_face;
    const Point<dim - 1> &xi   = pairing.master_reference_point;
    const Tensor<1, dim>  now  = master_surface->displacement(face, xi, ghosted_solution);
    pairing.master_point       = master_surface->reference_point(face, xi) + now;
    k.step_increment -= now - master_surface->displacement(face, xi, step_start);
  }

  template <int dim>
  bool
  ContactProblem<dim>::finite_strain() const
  {
    return std::any_of(materials.begin(), materials.end(), [](const auto &body) {
      return body.model->is_finite_strain();
    });
  }

  // ---------------------------------------------------------------------------
  // Evaluation on contact faces

  template <int dim>
  ContactProblem<dim>::FaceEvaluator::FaceEvaluator(const ContactProblem      &problem,
                                                    const Quadrature<dim - 1> &quadrature,
                                                    const bool                 follow_segments)
      : u_dofs(problem.fe_u->n_dofs_per_cell())
      , problem(problem)
      , quadrature(quadrature)
      , follow_segments(follow_segments)
  {
  }

  template <int dim>
  void
  ContactProblem<dim>::FaceEvaluator::reinit(const ContactFace                   &face,
                                             const TrilinosWrappers::MPI::Vector &ghosted)
  {
    const Quadrature<dim - 1> *wanted =
        (follow_segments && face.segments) ? face.segments.get() : nullptr;
    if (!u_values || wanted != current || wanted != nullptr)
      {
        const Quadrature<dim - 1> &rule = wanted ? *wanted : quadrature;
        u_values                        = std::make_unique<FEFaceValues<dim>>(
            *problem.fe_u, rule, update_values | update_quadrature_points | update_JxW_values);
        m_values = std::make_unique<FEFaceValues<dim>>(*problem.fe_m, rule, update_values);
        current  = wanted;
        u_now.resize(rule.size());
        u_start.resize(rule.size());
      }
    u_values->reinit(face.cell, face.face_no);
    const auto m_cell = problem.multiplier_cell(face.cell);
    m_values->reinit(m_cell, face.face_no);
    face.cell->get_dof_indices(u_dofs);

    std::vector<types::global_dof_index> all_m(problem.fe_m->n_dofs_per_cell());
    m_cell->get_dof_indices(all_m);
    m_dofs.clear();
    m_local.clear();
    m_coefficients.clear();
    for (unsigned int i = 0; i < all_m.size(); ++i)
      if (problem.fe_m->has_support_on_face(i, face.face_no))
        {
          Assert(all_m[i] < problem.n_multipliers, ExcInternalError());
          m_local.push_back(i);
          m_dofs.push_back(problem.n_u + all_m[i]);
          m_coefficients.push_back(ghosted(problem.n_u + all_m[i]));
        }

    const FiniteElement<dim> &fe = *problem.fe_u;
    for (unsigned int q = 0; q < u_now.size(); ++q)
      {
        u_now[q]   = 0.;
        u_start[q] = 0.;
        for (unsigned int i = 0; i < u_dofs.size(); ++i)
          {
            const unsigned int c   = fe.system_to_component_index(i).first;
            const double       phi = u_values->shape_value(i, q);
            u_now[q][c] += ghosted(u_dofs[i]) * phi;
            u_start[q][c] += problem.step_start(u_dofs[i]) * phi;
          }
      }
  }

  template <int dim>
  ContactKinematics<dim>
  ContactProblem<dim>::FaceEvaluator::kinematics(const unsigned int q) const
  {
    ContactKinematics<dim> k;
    k.displacement   = u_now[q];
    k.step_increment = u_now[q] - u_start[q];
    k.position       = u_values->quadrature_point(q) + u_now[q];
    k.JxW            = u_values->JxW(q);
    for (unsigned int a = 0; a < m_local.size(); ++a)
      {
        const unsigned int c   = problem.fe_m->system_to_component_index(m_local[a]).first;
        const double       psi = m_values->shape_value(m_local[a], q);
        if (c == 0)
          k.contact_pressure += m_coefficients[a] * psi;
        else
          k.semi_multiplier[c - 1] += m_coefficients[a] * psi;
      }
    return k;
  }

  template <int dim>
  void
  ContactProblem<dim>::update_pairings(const bool resegment)
  {
    if (master_surface)
      master_surface->update_configuration(ghosted_solution);
    const bool    new_points = resegment && update_segments();
    FaceEvaluator evaluator(*this, contact_quadrature);
    for (const auto &face : contact_faces)
      {
        evaluator.reinit(face, ghosted_solution);
        for (unsigned int q = 0; q < evaluator.n_points(); ++q)
          contact_states[face.first_point + q].pairing = pair(evaluator.kinematics(q).position);
      }
    if (new_points)
      {
        // the new points take the threshold and status of the current iterate,
        // which the loops would give them
        update_friction_thresholds();
        update_statuses();
      }
    if (master_surface && sparsity_ready && pairings_left_sparsity())
      setup_sparsity();
  }

  template <int dim>
  bool
  ContactProblem<dim>::update_segments()
  {
    if (dim != 2 || !master_surface)
      return false;
    FaceEvaluator                       ends(*this, QTrapezoid<dim - 1>(), false);
    std::vector<ContactFace>            faces;
    std::vector<ContactPointState<dim>> states;
    int                                 changed = 0;
    for (const auto &face : contact_faces)
      {
        ends.reinit(face, ghosted_solution);
        const Point<dim>     A      = ends.kinematics(0).position;
        const Tensor<1, dim> AB     = ends.kinematics(1).position - A;
        const double         length = AB.norm();
        BoundingBox<dim>     box(std::vector<Point<dim>>{A, A + AB});
        box.extend(0.5 * length);
        // the parameters in (0, 1) of the master's vertices projected on the face
        std::vector<double> cuts = {0., 1.};
        for (const auto &vertex : master_surface->vertices_near(box))
          {
            const double s = (vertex - A) * AB / (length * length);
            if (s > 1e-8 && s < 1. - 1e-8 && (vertex - (A + s * AB)).norm() <= length)
              cuts.push_back(s);
          }
        std::sort(cuts.begin(), cuts.end());
        cuts.erase(std::unique(cuts.begin(),
                               cuts.end(),
                               [](const double a, const double b) { return b - a < 1e-8; }),
                   cuts.end());
        ContactFace cut_face{
            face.cell, face.face_no, static_cast<unsigned int>(states.size()), nullptr};
        if (cuts.size() > 2)
          {
            std::vector<Point<dim - 1>> points;
            std::vector<double>         weights;
            for (unsigned int k = 0; k + 1 < cuts.size(); ++k)
              for (unsigned int q = 0; q < contact_quadrature.size(); ++q)
                {
                  const double width = cuts[k + 1] - cuts[k];
                  points.emplace_back(cuts[k] + width * contact_quadrature.point(q)[0]);
                  weights.push_back(width * contact_quadrature.weight(q));
                }
            cut_face.segments = std::make_shared<const Quadrature<dim - 1>>(points, weights);
          }
        const Quadrature<dim - 1> &old_rule = face_quadrature(face);
        const Quadrature<dim - 1> &new_rule = face_quadrature(cut_face);
        bool                       same     = old_rule.size() == new_rule.size();
        for (unsigned int q = 0; q < new_rule.size() && same; ++q)
          same = old_rule.point(q).distance(new_rule.point(q)) < 1e-12;
        if (same)
          {
            cut_face.segments = face.segments;
            states.insert(states.end(),
                          contact_states.begin() + face.first_point,
                          contact_states.begin() + face.first_point + old_rule.size());
          }
        else
          {
            changed = 1;
            states.resize(states.size() + new_rule.size());
          }
        faces.push_back(cut_face);
      }
    contact_faces  = faces;
    contact_states = states;
    return Utilities::MPI::max(changed, mpi_communicator) == 1;
  }

  template <int dim>
  void
  ContactProblem<dim>::update_ghosts()
  {
    ghosted_solution = solution;
  }

  template <int dim>
  void
  ContactProblem<dim>::assemble_newton_system(const bool assemble_matrix)
  {
    TimerOutput::Scope scope(timer, "assembly");
    ++work.assemblies;
    if (assemble_matrix)
      {
        ++work.jacobians;
        system_matrix = 0.;
      }
    system_rhs                = 0.;
    internal_force            = 0.;
    external_force            = 0.;
    multiplier_length_weights = 0.;
    inadmissible_state.clear();
    // the deformable master's pairings, folded into the generalized Newton, are
    // refreshed before the assembly: a new pairing may need a new sparsity pattern
    if (master_surface && folded(solver_parameters.geometry_method))
      update_pairings(false);
    assemble_volume(assemble_matrix);
    for (const auto &bc : boundary_conditions.neumann)
      bc.traction->check_finite(mpi_communicator);
    assemble_contact(assemble_matrix);
    if (assemble_matrix)
      system_matrix.compress(VectorOperation::add);
    system_rhs.compress(VectorOperation::add);
    internal_force.compress(VectorOperation::add);
    external_force.compress(VectorOperation::add);
    multiplier_length_weights.compress(VectorOperation::add);
    // every rank learns that one of them met an inadmissible state (the
    // messages are gathered only then)
    if (Utilities::MPI::max(static_cast<int>(!inadmissible_state.empty()), mpi_communicator) == 1)
      for (const auto &message : Utilities::MPI::all_gather(mpi_communicator, inadmissible_state))
        if (!message.empty())
          inadmissible_state = message;
  }

  template <int dim>
  void
  ContactProblem<dim>::assemble_volume(const bool assemble_matrix)
  {
    const FiniteElement<dim> &fe = *fe_u;
    FEValues<dim>             fe_values(fe, cell_quadrature, update_gradients | update_JxW_values);
    FEFaceValues<dim>         neumann_values(fe,
                                     QGauss<dim - 1>(fe_pair->displacement_degree() + 1),
                                     update_values | update_quadrature_points | update_JxW_values);
    const unsigned int        n_dofs = fe.n_dofs_per_cell();
    const unsigned int        n_q    = cell_quadrature.size();
    FullMatrix<double>        cell_matrix(n_dofs, n_dofs);
    Vector<double>            cell_rhs(n_dofs), cell_external(n_dofs);
    std::vector<types::global_dof_index> dofs(n_dofs);
    std::vector<double>                  coefficients(n_dofs);
    std::vector<unsigned int>            component(n_dofs);
    for (unsigned int i = 0; i < n_dofs; ++i)
      component[i] = fe.system_to_component_index(i).first;
    std::vector<Tensor<2, dim>> tangent_times_grad(n_dofs);

    for (const auto &cell : dof_handler_u.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          cell->get_dof_indices(dofs);
          for (unsigned int i = 0; i < n_dofs; ++i)
            coefficients[i] = ghosted_solution(dofs[i]);
          const Materials::Interface<dim> &material = material_of(cell);
          cell_matrix                               = 0.;
          cell_rhs                                  = 0.;
          for (unsigned int q = 0; q < n_q; ++q)
            {
              Tensor<2, dim> grad_u;
              for (unsigned int i = 0; i < n_dofs; ++i)
                grad_u[component[i]] += coefficients[i] * fe_values.shape_grad(i, q);
              Materials::Response<dim> response;
              try
                {
                  response =
                      material.evaluate(grad_u,
                                        material_history.committed(cell->active_cell_index(), q),
                                        material_history.trial(cell->active_cell_index(), q));
                }
              catch (const Materials::InadmissibleState &error)
                {
                  std::ostringstream where;
                  where << error.what() << " (in the cell centred at X = " << cell->center() << ")";
                  inadmissible_state = where.str();
                  return;
                }
              const double JxW = fe_values.JxW(q);
              for (unsigned int i = 0; i < n_dofs; ++i)
                cell_rhs(i) += response.stress[component[i]] * fe_values.shape_grad(i, q) * JxW;
              if (!assemble_matrix)
                continue;
              // A : ∇φ_j, where ∇φ_j has only the row component[j]
              for (unsigned int j = 0; j < n_dofs; ++j)
                {
                  const Tensor<1, dim> &g = fe_values.shape_grad(j, q);
                  for (unsigned int k = 0; k < dim; ++k)
                    for (unsigned int l = 0; l < dim; ++l)
                      tangent_times_grad[j][k][l] = response.tangent[k][l][component[j]] * g;
                }
              for (unsigned int i = 0; i < n_dofs; ++i)
                {
                  const Tensor<1, dim> gi = fe_values.shape_grad(i, q) * JxW;
                  for (unsigned int j = 0; j < n_dofs; ++j)
                    cell_matrix(i, j) += tangent_times_grad[j][component[i]] * gi;
                }
            }

          // the force scale of the scaled Newton criterion: internal forces
          // without the Dirichlet constraints, so their rows hold the reactions
          hanging_constraints.distribute_local_to_global(cell_rhs, dofs, internal_force);
          bool loaded = false;
          for (const auto &bc : boundary_conditions.neumann)
            for (const unsigned int f : cell->face_indices())
              if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == bc.boundary_id)
                {
                  if (!loaded)
                    cell_external = cell_rhs;
                  loaded = true;
                  add_neumann_contribution(cell, f, *bc.traction, neumann_values, cell_rhs);
                }
          if (loaded)
            {
              cell_external -= cell_rhs;
              hanging_constraints.distribute_local_to_global(cell_external, dofs, external_force);
            }

          add_to_global_system(cell_matrix, cell_rhs, dofs, assemble_matrix);
        }
  }

  template <int dim>
  void
  ContactProblem<dim>::add_neumann_contribution(
      const typename DoFHandler<dim>::active_cell_iterator &cell,
      const unsigned int                                    face_no,
      Parameters::BoundaryFunction<dim>                    &traction,
      FEFaceValues<dim>                                    &fe_face_values,
      Vector<double>                                       &cell_rhs) const
  {
    fe_face_values.reinit(cell, face_no);
    traction.set_time(time);
    Vector<double> t(dim);
    for (unsigned int q = 0; q < fe_face_values.n_quadrature_points; ++q)
      {
        traction.vector_value(fe_face_values.quadrature_point(q), t);
        for (unsigned int i = 0; i < fe_u->n_dofs_per_cell(); ++i)
          cell_rhs(i) -= t(fe_u->system_to_component_index(i).first) *
                         fe_face_values.shape_value(i, q) * fe_face_values.JxW(q);
      }
  }

  template <int dim>
  void
  ContactProblem<dim>::assemble_contact(const bool assemble_matrix)
  {
    FaceEvaluator             evaluator(*this, contact_quadrature);
    const unsigned int        n_u_cell = fe_u->n_dofs_per_cell();
    std::vector<unsigned int> u_component(n_u_cell);
    for (unsigned int i = 0; i < n_u_cell; ++i)
      u_component[i] = fe_u->system_to_component_index(i).first;
    // the generalized Newton's linearised pairing (a plane's does not move; a
    // deformable master's pairing is refreshed at every iterate, not linearised)
    const bool linearise_geometry =
        folded(solver_parameters.geometry_method) && !master_surface && !obstacle->is_flat();

    FullMatrix<double>                   local_matrix;
    Vector<double>                       local_rhs, length_weights;
    std::vector<types::global_dof_index> local_dofs;
    // the displacement DoFs of the local system: the slave cell's, then the
    // paired master faces' (their shape functions enter with a minus sign:
    // the gap is (x¹ − x²(ξ))·n)
    std::vector<Tensor<1, dim>>     phi;
    std::vector<double>             normal_shape;
    std::vector<Tensor<1, dim - 1>> tangential_shape;
    // ∂Δs/∂u_j: the tangential shape, plus (∂t_α/∂x φ_j)·Δu when the tangents move
    std::vector<Tensor<1, dim - 1>>                 slip_derivative;
    std::vector<types::global_dof_index>            master_dofs;
    std::vector<unsigned int>                       master_components;
    std::vector<double>                             master_values;
    std::map<types::global_dof_index, unsigned int> master_position;

    for (const auto &face : contact_faces)
      {
        evaluator.reinit(face, ghosted_solution);
        // the master DoFs of the face's pairings, once each
        master_position.clear();
        std::vector<types::global_dof_index> face_master_dofs;
        for (unsigned int q = 0; q < evaluator.n_points() && master_surface; ++q)
          {
            const int master_face = contact_states[face.first_point + q].pairing.master_face;
            for (const auto dof : master_surface->face_dof_indices(master_face))
              if (master_position.emplace(dof, n_u_cell + face_master_dofs.size()).second)
                face_master_dofs.push_back(dof);
          }
        const unsigned int n_d = n_u_cell + face_master_dofs.size();
        const unsigned int n_m = evaluator.m_dofs.size();
        const unsigned int n   = n_d + n_m;
        local_matrix.reinit(n, n);
        local_rhs.reinit(n);
        length_weights.reinit(n);
        local_dofs = evaluator.u_dofs;
        local_dofs.insert(local_dofs.end(), face_master_dofs.begin(), face_master_dofs.end());
        local_dofs.insert(local_dofs.end(), evaluator.m_dofs.begin(), evaluator.m_dofs.end());
        phi.resize(n_d);
        normal_shape.resize(n_d);
        tangential_shape.resize(n_d);
        slip_derivative.resize(n_d);
        std::vector<unsigned int> m_component(n_m);
        for (unsigned int a = 0; a < n_m; ++a)
          m_component[a] = fe_m->system_to_component_index(evaluator.m_local[a]).first;
        std::vector<double> psi(n_m);

        for (unsigned int q = 0; q < evaluator.n_points(); ++q)
          {
            ContactPointState<dim> &state = contact_states[face.first_point + q];
            ContactKinematics<dim>  k     = evaluator.kinematics(q);
            refresh_folded_state(state, k);
            const auto   point = point_response(state, k);
            const double w     = k.JxW;

            for (unsigned int i = 0; i < n_d; ++i)
              phi[i] = Tensor<1, dim>();
            for (unsigned int i = 0; i < n_u_cell; ++i)
              phi[i][u_component[i]] = evaluator.u_values->shape_value(i, q);
            if (state.pairing.master_face >= 0)
              {
                master_surface->shape_values(state.pairing.master_face,
                                             state.pairing.master_reference_point,
                                             master_dofs,
                                             master_components,
                                             master_values);
                for (unsigned int r = 0; r < master_dofs.size(); ++r)
                  phi[master_position[master_dofs[r]]][master_components[r]] -= master_values[r];
              }
            for (unsigned int i = 0; i < n_d; ++i)
              {
                normal_shape[i]     = phi[i] * state.pairing.normal;
                tangential_shape[i] = state.pairing.tangential_components(phi[i]);
                slip_derivative[i]  = tangential_shape[i];
                if (linearise_geometry)
                  for (unsigned int a = 0; a < dim - 1; ++a)
                    slip_derivative[i][a] +=
                        (state.pairing.tangent_gradients[a] * phi[i]) * k.step_increment;
              }
            for (unsigned int a = 0; a < n_m; ++a)
              psi[a] = evaluator.m_values->shape_value(evaluator.m_local[a], q);

            // the slave's tractions do work against δu¹, the master's (opposite)
            // against δu²(ξ); DESIGN §2
            const double             normal_traction     = point.normal_traction();
            const Tensor<1, dim - 1> tangential_traction = point.tangential_traction();
            const double             pressure_residual   = point.pressure_residual();
            const Tensor<1, dim - 1> semi_residual       = point.semi_multiplier_residual();
            for (unsigned int i = 0; i < n_d; ++i)
              local_rhs(i) -= w * (normal_traction * normal_shape[i] +
                                   tangential_traction * tangential_shape[i]);
            for (unsigned int a = 0; a < n_m; ++a)
              {
                local_rhs(n_d + a) +=
                    w * psi[a] *
                    (m_component[a] == 0 ? pressure_residual : semi_residual[m_component[a] - 1]);
                length_weights(n_d + a) +=
                    w * psi[a] * (m_component[a] == 0 ? 1. : point.semi_multiplier_weight());
              }
            if (!assemble_matrix)
              continue;

            // local_matrix(i, j) = ∂ local_rhs(i) / ∂ x_j
            const double             normal_stiffness     = point.normal_stiffness();
            const Tensor<2, dim - 1> tangential_stiffness = point.tangential_stiffness();
            const double             pressure_coupling    = point.pressure_coupling();
            const Tensor<2, dim - 1> friction_coupling    = point.friction_coupling();
            const double             pressure_compliance  = point.pressure_compliance();
            const Tensor<2, dim - 1> semi_block           = point.semi_multiplier_block();
            // ∂T/∂λ_n from the linearised threshold. The Λ rows keep their weight
            // s/r_t fixed at the iterate (doc/formulation.md): the derivative of the
            // weight, (s'/r_t)(Λ − P_B(ĝ)), vanishes at the solution and, large
            // away from it when r_t is small, only spoils the Newton steps.
            const Tensor<1, dim - 1> traction_slope =
                point.tangential_traction_pressure_derivative();
            for (unsigned int i = 0; i < n_d; ++i)
              {
                for (unsigned int j = 0; j < n_d; ++j)
                  {
                    double value =
                        normal_stiffness * normal_shape[i] * normal_shape[j] +
                        tangential_shape[i] * (tangential_stiffness * slip_derivative[j]);
                    if (linearise_geometry)
                      {
                        // the traction vector turns with n and t_α
                        value -=
                            normal_traction * (phi[i] * (state.pairing.normal_gradient * phi[j]));
                        for (unsigned int a = 0; a < dim - 1; ++a)
                          value -= tangential_traction[a] *
                                   (phi[i] * (state.pairing.tangent_gradients[a] * phi[j]));
                      }
                    local_matrix(i, j) += w * value;
                  }
                for (unsigned int b = 0; b < n_m; ++b)
                  {
                    const unsigned int c = m_component[b];
                    // u rows, multiplier columns
                    local_matrix(i, n_d + b) +=
                        w * psi[b] *
                        (c == 0 ? pressure_coupling * normal_shape[i] -
                                      traction_slope * tangential_shape[i]
                                : tangential_shape[i] * friction_coupling[c - 1]);
                    // multiplier rows, u columns
                    local_matrix(n_d + b, i) +=
                        w * psi[b] *
                        (c == 0 ? pressure_coupling * normal_shape[i]
                                : friction_coupling[c - 1] * slip_derivative[i]);
                  }
              }
            for (unsigned int a = 0; a < n_m; ++a)
              for (unsigned int b = 0; b < n_m; ++b)
                {
                  const unsigned int ca = m_component[a], cb = m_component[b];
                  double             block = 0.;
                  if (ca == 0 && cb == 0)
                    block = pressure_compliance;
                  else if (ca > 0 && cb > 0)
                    block = semi_block[ca - 1][cb - 1];
                  local_matrix(n_d + a, n_d + b) += w * block * psi[a] * psi[b];
                }
          }
        newton_constraints.distribute_local_to_global(
            length_weights, local_dofs, multiplier_length_weights);
        add_to_global_system(local_matrix, local_rhs, local_dofs, assemble_matrix);
      }
  }

  template <int dim>
  void
  ContactProblem<dim>::add_to_global_system(const FullMatrix<double> &local_matrix,
                                            Vector<double>           &local_rhs,
                                            const std::vector<types::global_dof_index> &dofs,
                                            const bool assemble_matrix)
  {
    if (!assemble_matrix)
      {
        newton_constraints.distribute_local_to_global(local_rhs, dofs, system_rhs);
        return;
      }
    // Tangent predictor: the residual linearised at u + Δū, R(u) + K Δū, where
    // Δū is the Dirichlet increment of the load step (zero off the Dirichlet
    // boundary), so the first solve carries the boundary motion into the body.
    if (dirichlet_predictor)
      for (unsigned int i = 0; i < dofs.size(); ++i)
        for (unsigned int j = 0; j < dofs.size(); ++j)
          local_rhs(i) += local_matrix(i, j) * dirichlet_increment(dofs[j]);
    newton_constraints.distribute_local_to_global(
        local_matrix, local_rhs, dofs, system_matrix, system_rhs);
  }

  template <int dim>
  Contact::PointResponse<dim - 1>
  ContactProblem<dim>::point_response(const ContactPointState<dim> &state,
                                      const ContactKinematics<dim> &k) const
  {
    return Contact::PointResponse<dim - 1>(
        k.contact_pressure,
        state.pairing.gap(k.position),
        k.semi_multiplier,
        state.pairing.tangential_components(k.step_increment),
        state.in_contact,
        state.friction_threshold,
        friction_law->has_friction(),
        contact_parameters.r_n,
        contact_parameters.r_t,
        folded(solver_parameters.friction_method)
            ? friction_law->threshold_derivative(threshold_pressure(k.contact_pressure))
            : 0.);
  }

  template <int dim>
  void
  ContactProblem<dim>::refresh_folded_state(ContactPointState<dim> &state,
                                            ContactKinematics<dim> &k) const
  {
    // (a deformable master's pairings are refreshed before the assembly)
    if (folded(solver_parameters.geometry_method) && !master_surface)
      state.pairing = obstacle->project(k.position);
    follow_master(state.pairing, k);
    if (folded(solver_parameters.friction_method) && friction_law->threshold_depends_on_pressure())
      state.friction_threshold = friction_law->threshold(threshold_pressure(k.contact_pressure));
    if (folded(solver_parameters.status_method))
      state.in_contact = status(state, k);
  }

  template <int dim>
  bool
  ContactProblem<dim>::status(const ContactPointState<dim> &state,
                              const ContactKinematics<dim> &k) const
  {
    // A gap within round-off of zero touches: a body resting on the obstacle
    // by a vertex placed 1e-14 mm above it must start in contact, as one at
    // exactly zero does, or a load-controlled body has no support at all.
    const double gap = state.pairing.gap(k.position);
    return Contact::is_in_contact(Contact::augmented_pressure(
        k.contact_pressure, std::abs(gap) <= touching_gap ? 0. : gap, contact_parameters.r_n));
  }

  template <int dim>
  double
  ContactProblem<dim>::threshold_pressure(const double contact_pressure) const
  {
    return contact_pressure > negligible_pressure ? contact_pressure : 0.;
  }

  template <int dim>
  double
  ContactProblem<dim>::residual_norm() const
  {
    TrilinosWrappers::MPI::Vector scaled(system_rhs);
    scaled.scale(residual_scaling);
    return scaled.linfty_norm();
  }

  template <int dim>
  ScaledResidual
  ContactProblem<dim>::scaled_residual() const
  {
    // largest: force residual, force scale, gap, slip, displacement
    double largest[5] = {0., 0., 0., 0., 0.};
    for (const auto i : locally_owned_u)
      {
        largest[0] = std::max(largest[0], std::abs(system_rhs(i)));
        largest[1] =
            std::max({largest[1], std::abs(internal_force(i)), std::abs(external_force(i))});
        largest[4] = std::max(largest[4], std::abs(solution(i)));
      }
    for (const auto &[row, component] : owned_multiplier_components)
      if (multiplier_length_weights(row) > 0.)
        {
          double &block = largest[component == 0 ? 2 : 3];
          block = std::max(block, std::abs(system_rhs(row)) / multiplier_length_weights(row));
        }
    Utilities::MPI::max(largest, mpi_communicator, largest);
    // Floor of the force scale: where the body moves without deforming (a
    // rigid motion before contact, a free rotation) the forces are round-off,
    // so forces below those that displace a node of the stiffest, smallest
    // cell by a fraction force_scale_floor of the largest displacement count
    // as zero (doc/formulation.md).
    largest[1] = std::max(largest[1], force_scale_floor * nodal_stiffness * largest[4]);
    // a zero residual is converged even where its scale is zero (a body at rest)
    const auto ratio = [](const double value, const double scale) {
      return value == 0.  ? 0.
             : scale > 0. ? value / scale
                          : std::numeric_limits<double>::infinity();
    };
    return ScaledResidual{ratio(largest[0], largest[1]),
                          ratio(largest[2], largest[4]),
                          ratio(largest[3], largest[4])};
  }

  template <int dim>
  void
  ContactProblem<dim>::compute_contact_statistics(StepStatistics &stats)
  {
    unsigned int   counts[4]    = {0, 0, 0, 0}; // all, in contact, stick, slip
    double         normal_force = 0.;
    Tensor<1, dim> total_force, tangential_force;
    double         largest_displacement = 0.;
    for (const auto i : locally_owned_u)
      largest_displacement = std::max(largest_displacement, std::abs(solution(i)));
    // the multiplier equations of the converged iterate (system_rhs is its residual)
    Contact::FrictionLawCheck<dim> check(largest_displacement);
    for (const auto &[row, component] : owned_multiplier_components)
      if (multiplier_length_weights(row) > 0.)
        check.add_multiplier_row(component == 0,
                                 std::abs(system_rhs(row)) / multiplier_length_weights(row));
    for_each_contact_point([&](ContactPointState<dim> &state, const ContactKinematics<dim> &k) {
      const auto point = point_response(state, k);
      ++counts[0];
      if (point.status() == Contact::Status::open)
        return;
      ++counts[1];
      ++counts[point.status() == Contact::Status::stick ? 2 : 3];
      check.add_point(k.position - k.displacement,
                      point.tangential_traction().norm(),
                      friction_law->threshold(threshold_pressure(k.contact_pressure)));
      active_set.push_back(k.position - k.displacement);
      normal_force += k.JxW * point.normal_traction();
      total_force += k.JxW * point.normal_traction() * state.pairing.normal;
      tangential_force +=
          k.JxW * state.pairing.from_tangential_components(point.tangential_traction());
    });
    total_force += tangential_force;
    stats.contact_points            = Utilities::MPI::sum(counts[0], mpi_communicator);
    stats.points_in_contact         = Utilities::MPI::sum(counts[1], mpi_communicator);
    stats.points_stick              = Utilities::MPI::sum(counts[2], mpi_communicator);
    stats.points_slip               = Utilities::MPI::sum(counts[3], mpi_communicator);
    stats.normal_force              = Utilities::MPI::sum(normal_force, mpi_communicator);
    const Tensor<1, dim> total      = Utilities::MPI::sum(total_force, mpi_communicator);
    const Tensor<1, dim> tangential = Utilities::MPI::sum(tangential_force, mpi_communicator);
    stats.tangential_force          = tangential.norm();
    for (unsigned int d = 0; d < dim; ++d)
      stats.contact_force[d] = total[d];
    stats.friction_law_violations =
        check.gather(mpi_communicator, solver_parameters.friction_tolerance);
    stats.friction_law_report = check.report();
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
  ContactProblem<dim>::refine_mesh()
  {
    if (adaptive_refinement.criterion == Parameters::AdaptiveRefinement::Criterion::active_set)
      refine_around_active_set();
    else
      {
        // Kelly indicators of the displacement of the last converged state
        const TrilinosWrappers::MPI::Vector u = ghosted_displacement();
        Vector<float>                       indicators(triangulation.n_active_cells());
        KellyErrorEstimator<dim>::estimate(
            dof_handler_u, QGauss<dim - 1>(fe_pair->displacement_degree() + 1), {}, u, indicators);
        parallel::distributed::GridRefinement::refine_and_coarsen_fixed_number(
            triangulation, indicators, adaptive_refinement.fraction, 0.);
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
    triangulation.execute_coarsening_and_refinement();
  }

  template <int dim>
  void
  ContactProblem<dim>::check_memory_for_growth(const double growth) const
  {
    // The peak memory of this rank so far (the largest mesh yet, with its
    // factorisation) scaled by the growth of the mesh, to the power of the
    // direct solver's fill (about n log n in 2D, n^(4/3) in 3D), against the
    // physical memory shared by the ranks of this node.
    Utilities::System::MemoryStats memory;
    Utilities::System::get_memory_stats(memory);
    const double fill = std::pow(growth, dim == 3 ? 4. / 3. : 1.1);
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
        triangulation.refine_global(1);
        return;
      }
    // the band scales with the size of the active zone (its bounding box's
    // diameter), so the material below the contact, where the stresses vary
    // over that size, is refined too; the half cell diameter keeps the cells
    // that contain active points
    const auto   box = BoundingBox<dim>(points);
    const double zone_size =
        box.get_boundary_points().first.distance(box.get_boundary_points().second);
    const auto tree = pack_rtree(points);
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          std::vector<Point<dim>> nearest;
          tree.query(boost::geometry::index::nearest(cell->center(), 1),
                     std::back_inserter(nearest));
          if (cell->center().distance(nearest[0]) <=
              adaptive_refinement.band * zone_size + 0.5 * cell->diameter())
            cell->set_refine_flag();
        }
  }

  template class ContactProblem<2>;
  template class ContactProblem<3>;
} // namespace StabilizedLagrangian
