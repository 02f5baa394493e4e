#include <deal.II/base/mpi.h>

#include <deal.II/grid/grid_tools.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/vector.h>

#include <stabilized_lagrangian/contact/stabilized_lagrangian.h>
#include <stabilized_lagrangian/solver/contact_problem.h>

#include <cmath>
#include <limits>
#include <sstream>

namespace StabilizedLagrangian
{
  template <int dim>
  std::string
  ContactProblem<dim>::rigid_motions_left_free(const bool with_contact) const
  {
    // The rigid motions (dim translations, then the rotations about the
    // body's centre, scaled by its size) restricted to the prescribed
    // components of the Dirichlet vertices and the springs' held ones: G =
    // Σ m mᵀ over those (vertex, component) pairs; the eigenvectors of G with
    // a zero eigenvalue are the motions no support holds.
    if (!partner->is_rigid())
      return ""; // two bodies: each is held by the other or by its conditions
    if (axisymmetric)
      {
        // the hoop strain holds u_r: the one rigid motion is along the axis
        bool                                          held = false;
        std::vector<BoundaryConditions::Support<dim>> supports;
        for (const auto &condition : boundary_conditions)
          condition->add_supports(supports);
        for (const auto &support : supports)
          held = held || support.held[1];
        if (with_contact)
          for (const auto id : chosen.contact_boundaries)
            for_each_boundary_vertex(id, [&](const Point<dim> &vertex) {
              held = held || any_friction() || std::abs(partner->project(vertex).normal[1]) > 1e-6;
            });
        held = Utilities::MPI::logical_or(held, mpi_communicator);
        return held ? "" : "the translation along y";
      }
    const unsigned int n_rotations = dim == 2 ? 1 : 3;
    const unsigned int n_modes     = dim + n_rotations;
    const auto         box         = GridTools::compute_bounding_box(triangulation);
    const Point<dim>   centre      = box.center();
    double             size        = 0.;
    for (unsigned int d = 0; d < dim; ++d)
      size = std::max(size, box.side_length(d));
    FullMatrix<double> gram(n_modes, n_modes);
    Vector<double>     m(n_modes);
    // the supports: the prescribed components, and the springs' stiff ones
    std::vector<BoundaryConditions::Support<dim>> supports;
    for (const auto &condition : boundary_conditions)
      condition->add_supports(supports);
    // a support holding the direction n at a vertex: m_i = n · (mode i there)
    const auto add_direction = [&](const Point<dim> &vertex, const Tensor<1, dim> &n) {
      const Tensor<1, dim> x = (vertex - centre) / size;
      m                      = 0.;
      for (unsigned int d = 0; d < dim; ++d)
        m[d] = n[d];
      // the rotations ω × x (2D: about z)
      if (dim == 2)
        m[dim] = -n[0] * x[1] + n[1] * x[0];
      else
        for (unsigned int axis = 0; axis < 3; ++axis)
          {
            Tensor<1, 3> w, xx, nn;
            w[axis] = 1.;
            for (unsigned int i = 0; i < dim; ++i)
              {
                xx[i] = x[i];
                nn[i] = n[i];
              }
            m[dim + axis] = cross_product_3d(w, xx) * nn;
          }
      for (unsigned int i = 0; i < n_modes; ++i)
        for (unsigned int j = 0; j < n_modes; ++j)
          gram(i, j) += m[i] * m[j];
    };
    const auto add_support = [&](const Point<dim> &vertex, const std::vector<bool> &held) {
      for (unsigned int d = 0; d < dim; ++d)
        if (held[d])
          {
            Tensor<1, dim> e;
            e[d] = 1.;
            add_direction(vertex, e);
          }
    };
    for (const auto &support : supports)
      if (support.boundary)
        for_each_boundary_vertex(*support.boundary, [&](const Point<dim> &vertex) {
          add_support(vertex, support.held);
        });
    // each point condition's vertex, counted once (by rank 0: the sum below adds the ranks)
    if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      for (const auto &support : supports)
        if (!support.boundary)
          add_support(support.point, support.held);
    // the contact boundary: along the obstacle's normal, or wholly with friction
    if (with_contact)
      for (const auto id : chosen.contact_boundaries)
        for_each_boundary_vertex(id, [&](const Point<dim> &vertex) {
          if (any_friction())
            add_support(vertex, std::vector<bool>(dim, true));
          else
            add_direction(vertex, partner->project(vertex).normal);
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
  void
  ContactProblem<dim>::check_body_is_held() const
  {
    if (!partner->is_rigid() || any_friction())
      return;
    const std::string free = rigid_motions_left_free(true);
    // (a warning: without a load along that motion the singular system has
    // solutions, which the direct solver finds)
    if (!free.empty())
      pcout << "WARNING: the body is not held: the contact is frictionless (Contact/Friction "
               "law), so it holds the body only along the obstacle's normal, and with the "
               "Dirichlet conditions and springs it leaves "
            << free
            << " free; the Newton system is singular, and a load along that motion has no "
               "equilibrium. Hold that motion with a Dirichlet condition (Boundary "
               "conditions/Dirichlet <name>, on a boundary or at one node with Point) or a "
               "spring, or give the contact friction.\n";
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
    // Nothing touches and a rigid motion is free (the Dirichlet conditions
    // leave it, or the Newton system proved singular: a body carried only by
    // prescribed forces): the loads alone cannot bring the body onto its
    // partner in a quasi-static step. It is put on the partner by its points
    // nearest to it, as a body lowered until it touches; those points count
    // as touching (approach_gap) until the step converges.
    double nearest = std::numeric_limits<double>::max();
    for_each_contact_point([&](ContactPointState<dim> &state, const ContactKinematics<dim> &k) {
      nearest = std::min(nearest, state.pairing.gap(k.position));
    });
    nearest                     = Utilities::MPI::min(nearest, mpi_communicator);
    contact_start.approach_gap  = std::max(nearest, 0.) + touching_gap;
    contact_start.approach_used = true;
    // the conditions' own gaps (the nodes' weighted gaps): the nearest closes
    contact_start.approach_gap = std::max(
        contact_start.approach_gap, std::max(conditions->least_gap(nearest), 0.) + touching_gap);
    conditions->close_nearest(nearest, touching_gap);
    pcout << "  nothing touches the "
          << (free_rigid_motions.empty()
                  ? std::string("partner and the Newton system is singular")
                  : "obstacle and the Dirichlet conditions leave " + free_rigid_motions + " free")
          << ": the " << points_in_contact() << " contact point(s) nearest to it (gap " << nearest
          << " mm) start in contact\n";
  }

  namespace
  {
    /**
     * The Poisson's ratio from which displacements of degree @p degree lock
     * volumetrically: Q1 from K/G ≈ 50 (ν ≈ 0.49), Q2 much later.
     */
    double
    locking_poissons_ratio(const unsigned int degree)
    {
      return degree == 1 ? 0.49 : 0.4999;
    }
  } // namespace

  template <int dim>
  void
  ContactProblem<dim>::warn_if_pair_locks() const
  {
    // Volumetric locking: with a bulk modulus far above the shear modulus,
    // K/G = 2(1 + ν)/(3(1 − 2ν)), low-order displacements cannot deform at
    // constant volume and the body answers far too stiffly (a block of
    // ν = 0.4999 pressed on a plane with Q1/P1: 3.6 times the normal force of
    // Q2/P2).
    const double limit = locking_poissons_ratio(fe_pair->displacement_degree());
    for (const auto &material : materials)
      {
        const double nu = material.model->poissons_ratio();
        // F-bar and mixed keep one volume constraint per cell (mixed on Q2:
        // dim + 1): locking-free on Q1 and Q2, not on linear simplices, whose
        // gradient is already constant in the cell (mixed is refused there)
        if (nu < limit || (material.modified_volume() && !simplex_mesh()) ||
            material.volumetric == Materials::BodyMaterial<dim>::Volumetric::mixed)
          continue;
        pcout << "WARNING: " << material.slot << ": Poisson's ratio " << nu << " (bulk modulus "
              << 2. * (1. + nu) / (3. * (1. - 2. * nu))
              << " times the shear modulus) with displacements of degree "
              << fe_pair->displacement_degree()
              << " (Contact/Finite element pair = " << contact_parameters.fe_pair
              << "): the body locks volumetrically, its displacements and forces are far too "
                 "stiff. Use "
              << (simplex_mesh() ? "quadratic displacements (P2/P1, P2/P2) with " : "")
              << material.slot
              << "/Volumetric formulation = " << (simplex_mesh() ? "mixed " : "F-bar or mixed ")
              << "(locking-free; doc/formulation.md \"Near incompressibility\").\n";
      }
  }

  template <int dim>
  void
  ContactProblem<dim>::warn_if_stick_traction_oscillates() const
  {
    // F-bar and mixed on Q1 keep one volume change per cell: the Q1/P0 pair of
    // the mean dilatation, which is not inf-sup stable. Its checkerboard
    // pressure exerts a tangential force alternating from node to node on the
    // contact boundary; where stick holds each contact node tangentially (a
    // multiplier per node), the friction multiplier takes that force up. When
    // ν → 0.5 the frictional traction of Hertz's contact on a rigid plane
    // vanishes with Dundurs' β = (1 − 2ν)/(2(1 − ν)), so the alternation is
    // most of the stick-zone traction (doc/near_incompressibility.md,
    // "Stick-zone traction").
    if (!any_friction() || fe_pair->displacement_degree() != 1 || simplex_mesh() ||
        fe_pair->multiplier_on_coarser_mesh())
      return;
    for (const auto &material : materials)
      {
        const double nu = material.model->poissons_ratio();
        if (!material.modified_volume() || nu < locking_poissons_ratio(1))
          continue;
        pcout << "WARNING: " << material.slot << ": Poisson's ratio " << nu
              << " with Volumetric formulation = "
              << (material.volumetric == Materials::BodyMaterial<dim>::Volumetric::f_bar ? "F-bar"
                                                                                         : "mixed")
              << " on Q1 (one volume change per cell, the Q1/P0 pair, not inf-sup stable) and "
                 "friction multipliers at every contact node (Contact/Finite element pair = "
              << contact_parameters.fe_pair
              << "): the stick-zone tangential traction alternates from node to node (the "
                 "pressure checkerboard mode). Use Contact/Finite element pair = Q1/P1 coarse, or "
                 "Q2/P1 with "
              << material.slot
              << "/Volumetric formulation = mixed (doc/near_incompressibility.md, \"Stick-zone "
                 "traction\").\n";
      }
  }

  template <int dim>
  void
  ContactProblem<dim>::warn_if_body_behind_obstacle() const
  {
    if (!partner->is_rigid())
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
            behind += partner->project(cell->vertex(v)).gap(cell->vertex(v)) < -tolerance;
          }
    behind   = Utilities::MPI::sum(behind, mpi_communicator);
    vertices = Utilities::MPI::sum(vertices, mpi_communicator);
    if (2 * behind > vertices)
      pcout << "WARNING: " << behind << " of " << vertices
            << " cell vertices lie behind the obstacle's surface (negative gap) before the first "
               "step. The obstacle's normal must point out of the obstacle, towards the body: "
               "check the `Obstacle` entries (a plane's Normal, for instance).\n";
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
          if (is_slave_or_master_face(cell, f))
            E = std::min(E, material_of(cell).youngs_modulus());
    E = Utilities::MPI::min(E, mpi_communicator);
    if (contact_parameters.r_n_automatic)
      {
        chosen.r_n = contact_parameters.r_n_factor * Contact::automatic_r_n_constant * E / h;
        pcout << "  r_n = automatic: " << contact_parameters.r_n_factor << " x "
              << Contact::automatic_r_n_constant << " E/h = " << chosen.r_n << " N/mm^3 (E = " << E
              << " MPa, h = " << h << " mm)\n";
      }
    if (contact_parameters.r_t_automatic)
      {
        // without prescribed motion, the contact mesh size is the length scale
        const double increment = largest_dirichlet_increment();
        const double length    = increment > 0. ? increment : h;
        chosen.r_t = contact_parameters.r_t_factor * Contact::automatic_r_t_constant / length;
        pcout << "  r_t = automatic: " << contact_parameters.r_t_factor << " x "
              << Contact::automatic_r_t_constant << "/l = " << chosen.r_t << " 1/mm (l = " << length
              << " mm, "
              << (increment > 0. ? "the largest prescribed displacement increment of a load step"
                                 : "h: no prescribed displacement increment")
              << ")\n";
      }
  }

  template <int dim>
  double
  ContactProblem<dim>::largest_dirichlet_increment()
  {
    const BoundaryConditions::LoadSteps steps{load_stepping.end_time / load_stepping.n_steps,
                                              load_stepping.n_steps};
    double                              increment = 0.;
    for (const auto &condition : boundary_conditions)
      increment = std::max(increment, condition->largest_increment(boundary_view(), steps));
    return Utilities::MPI::max(increment, mpi_communicator);
  }

  template <int dim>
  void
  ContactProblem<dim>::warn_if_dirichlet_not_ramped() const
  {
    for (const auto &condition : boundary_conditions)
      condition->warn_if_not_ramped(boundary_view(), pcout);
  }

  // Explicit instantiation of the members defined in this file (the class
  // itself is instantiated once, in contact_problem.cc).
#define SL_INSTANTIATE(dim)                                                             \
  template std::string  ContactProblem<dim>::rigid_motions_left_free(bool) const;       \
  template void         ContactProblem<dim>::check_body_is_held() const;                \
  template unsigned int ContactProblem<dim>::points_in_contact() const;                 \
  template void         ContactProblem<dim>::close_nearest_points();                    \
  template void         ContactProblem<dim>::warn_if_pair_locks() const;                \
  template void         ContactProblem<dim>::warn_if_stick_traction_oscillates() const; \
  template void         ContactProblem<dim>::warn_if_body_behind_obstacle() const;      \
  template void         ContactProblem<dim>::choose_augmentation_parameters();          \
  template double       ContactProblem<dim>::largest_dirichlet_increment();             \
  template void         ContactProblem<dim>::warn_if_dirichlet_not_ramped() const;

  SL_INSTANTIATE(2)
  SL_INSTANTIATE(3)
#undef SL_INSTANTIATE
} // namespace StabilizedLagrangian
