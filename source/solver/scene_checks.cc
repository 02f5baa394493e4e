#include <deal.II/base/mpi.h>

#include <deal.II/grid/grid_tools.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/vector.h>

#include <stabilized_lagrangian/contact/stabilized_lagrangian.h>
#include <stabilized_lagrangian/solver/scene_checks.h>

#include <cmath>
#include <limits>
#include <sstream>

namespace StabilizedLagrangian
{
  template <int dim>
  SceneChecks<dim>::SceneChecks(const View &view)
      : view(view)
  {
  }

  template <int dim>
  void
  SceneChecks<dim>::warn_before_run() const
  {
    check_body_is_held();
    if (!warn_if_body_behind_obstacle())
      warn_if_body_passes_through_obstacle();
    warn_if_pair_locks();
    warn_if_stick_traction_oscillates();
    warn_of_boundary_conditions();
    warn_if_obstacle_motion_ignored();
    warn_if_obstacle_not_of_revolution();
  }

  template <int dim>
  std::vector<BoundaryConditions::Support<dim>>
  SceneChecks<dim>::supports() const
  {
    std::vector<BoundaryConditions::Support<dim>> supports;
    for (const auto &condition : view.boundary_conditions)
      condition->add_supports(supports);
    return supports;
  }

  template <int dim>
  std::string
  SceneChecks<dim>::rigid_motions_left_free(const bool with_contact) const
  {
    // The rigid motions (dim translations, then the rotations about the
    // body's centre, scaled by its size) restricted to the prescribed
    // components of the Dirichlet vertices and the springs' held ones: G =
    // Σ m mᵀ over those (vertex, component) pairs; the eigenvectors of G with
    // a zero eigenvalue are the motions no support holds.
    if (!view.partner->is_rigid())
      return ""; // two bodies: each is held by the other or by its conditions
    if (view.axisymmetric)
      return axial_translation_held(with_contact) ? "" : "the translation along y";
    return describe_free_motions(rigid_motion_gram(with_contact));
  }

  template <int dim>
  bool
  SceneChecks<dim>::axial_translation_held(const bool with_contact) const
  {
    // the hoop strain holds u_r: the one rigid motion is along the axis
    bool held = false;
    for (const auto &support : supports())
      held = held || support.held[1];
    if (with_contact)
      for (const auto id : view.contact_boundaries)
        for_each_boundary_vertex(id, [&](const Point<dim> &vertex) {
          held =
              held || view.any_friction || std::abs(view.partner->project(vertex).normal[1]) > 1e-6;
        });
    return Utilities::MPI::logical_or(held, view.communicator);
  }

  template <int dim>
  FullMatrix<double>
  SceneChecks<dim>::rigid_motion_gram(const bool with_contact) const
  {
    const unsigned int n_rotations = dim == 2 ? 1 : 3;
    const unsigned int n_modes     = dim + n_rotations;
    const auto         box         = GridTools::compute_bounding_box(view.triangulation);
    const Point<dim>   centre      = box.center();
    double             size        = 0.;
    for (unsigned int d = 0; d < dim; ++d)
      size = std::max(size, box.side_length(d));
    FullMatrix<double> gram(n_modes, n_modes);
    Vector<double>     m(n_modes);
    // the supports: the prescribed components, and the springs' stiff ones
    const std::vector<BoundaryConditions::Support<dim>> supports = this->supports();
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
    if (Utilities::MPI::this_mpi_process(view.communicator) == 0)
      for (const auto &support : supports)
        if (!support.boundary)
          add_support(support.point, support.held);
    // the contact boundary: along the obstacle's normal, or wholly with friction
    if (with_contact)
      for (const auto id : view.contact_boundaries)
        for_each_boundary_vertex(id, [&](const Point<dim> &vertex) {
          if (view.any_friction)
            add_support(vertex, std::vector<bool>(dim, true));
          else
            add_direction(vertex, view.partner->project(vertex).normal);
        });
    Utilities::MPI::sum(gram, view.communicator, gram);
    return gram;
  }

  template <int dim>
  std::string
  SceneChecks<dim>::describe_free_motions(const FullMatrix<double> &gram)
  {
    const unsigned int n_modes = gram.m();
    double             trace   = 0.;
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
  SceneChecks<dim>::check_body_is_held() const
  {
    if (!view.partner->is_rigid() || view.any_friction)
      return;
    const std::string free = rigid_motions_left_free(true);
    // (a warning: without a load along that motion the singular system has
    // solutions, which the direct solver finds)
    if (!free.empty())
      view.pcout << "WARNING: the body is not held: the contact is frictionless (Contact/Friction "
                    "law), so it holds the body only along the obstacle's normal, and with the "
                    "Dirichlet conditions and springs it leaves "
                 << free
                 << " free; the Newton system is singular, and a load along that motion has no "
                    "equilibrium. Hold that motion with a Dirichlet condition (Boundary "
                    "conditions/Dirichlet <name>, on a boundary or at one node with Point) or a "
                    "spring, or give the contact friction.\n";
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

    /** Whether face @p f of @p cell lies on one of the @p boundaries. */
    template <typename CellIterator>
    bool
    is_on(const CellIterator                 &cell,
          const unsigned int                  f,
          const std::set<types::boundary_id> &boundaries)
    {
      return cell->face(f)->at_boundary() && boundaries.count(cell->face(f)->boundary_id()) > 0;
    }
  } // namespace

  template <int dim>
  void
  SceneChecks<dim>::warn_if_pair_locks() const
  {
    // Volumetric locking: with a bulk modulus far above the shear modulus,
    // K/G = 2(1 + ν)/(3(1 − 2ν)), low-order displacements cannot deform at
    // constant volume and the body answers far too stiffly (a block of
    // ν = 0.4999 pressed on a plane with Q1/P1: 3.6 times the normal force of
    // Q2/P2).
    const double limit = locking_poissons_ratio(view.fe_pair.displacement_degree());
    for (const auto &material : view.materials)
      {
        const double nu = material.model->poissons_ratio();
        // F-bar and mixed keep one volume constraint per cell (mixed on Q2:
        // dim + 1): locking-free on Q1 and Q2, not on linear simplices, whose
        // gradient is already constant in the cell (mixed is refused there)
        if (nu < limit || (material.modified_volume() && !view.simplex) ||
            material.volumetric == Materials::BodyMaterial<dim>::Volumetric::mixed)
          continue;
        view.pcout << "WARNING: " << material.slot << ": Poisson's ratio " << nu
                   << " (bulk modulus " << 2. * (1. + nu) / (3. * (1. - 2. * nu))
                   << " times the shear modulus) with displacements of degree "
                   << view.fe_pair.displacement_degree()
                   << " (Contact/Finite element pair = " << view.contact_parameters.fe_pair
                   << "): the body locks volumetrically, its displacements and forces are far too "
                      "stiff. Use "
                   << (view.simplex ? "quadratic displacements (P2/P1, P2/P2) with " : "")
                   << material.slot
                   << "/Volumetric formulation = " << (view.simplex ? "mixed " : "F-bar or mixed ")
                   << "(locking-free; doc/formulation.md \"Near incompressibility\").\n";
      }
  }

  template <int dim>
  void
  SceneChecks<dim>::warn_if_stick_traction_oscillates() const
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
    if (!view.any_friction || view.fe_pair.displacement_degree() != 1 || view.simplex ||
        view.fe_pair.multiplier_on_coarser_mesh())
      return;
    for (const auto &material : view.materials)
      {
        const double nu = material.model->poissons_ratio();
        if (!material.modified_volume() || nu < locking_poissons_ratio(1))
          continue;
        view.pcout
            << "WARNING: " << material.slot << ": Poisson's ratio " << nu
            << " with Volumetric formulation = "
            << (material.volumetric == Materials::BodyMaterial<dim>::Volumetric::f_bar ? "F-bar"
                                                                                       : "mixed")
            << " on Q1 (one volume change per cell, the Q1/P0 pair, not inf-sup stable) and "
               "friction multipliers at every contact node (Contact/Finite element pair = "
            << view.contact_parameters.fe_pair
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
  SceneChecks<dim>::choose_augmentation_parameters(ChosenParameters &chosen) const
  {
    if (!view.contact_parameters.r_n_automatic && !view.contact_parameters.r_t_automatic)
      return;
    double h = 0.;
    for (const auto &cell : view.triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int f : cell->face_indices())
          if (is_on(cell, f, view.contact_boundaries))
            h = std::max(h, cell->face(f)->diameter());
    h = Utilities::MPI::max(h, view.communicator);
    AssertThrow(h > 0., ExcMessage("the contact boundary has no faces"));
    // E of the softest body at the contact (slave or master): with a rigid
    // obstacle the slave's; with two bodies the softer one's, because there the
    // solution depends on r_n (doc/formulation.md, two deformable bodies) and the
    // rigid limit of a stiffening master must keep the slave's r_n
    double E = std::numeric_limits<double>::max();
    for (const auto &cell : view.triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int f : cell->face_indices())
          if (is_on(cell, f, view.contact_boundaries) || is_on(cell, f, view.master_boundaries))
            E = std::min(E, view.material_of(cell).youngs_modulus());
    E = Utilities::MPI::min(E, view.communicator);
    if (view.contact_parameters.r_n_automatic)
      {
        chosen.r_n = view.contact_parameters.r_n_factor * Contact::automatic_r_n_constant * E / h;
        view.pcout << "  r_n = automatic: " << view.contact_parameters.r_n_factor << " x "
                   << Contact::automatic_r_n_constant << " E/h = " << chosen.r_n
                   << " N/mm^3 (E = " << E << " MPa, h = " << h << " mm)\n";
      }
    if (view.contact_parameters.r_t_automatic)
      {
        // without prescribed motion, the contact mesh size is the length scale
        const double increment = largest_dirichlet_increment();
        const double length    = increment > 0. ? increment : h;
        chosen.r_t = view.contact_parameters.r_t_factor * Contact::automatic_r_t_constant / length;
        view.pcout << "  r_t = automatic: " << view.contact_parameters.r_t_factor << " x "
                   << Contact::automatic_r_t_constant << "/l = " << chosen.r_t
                   << " 1/mm (l = " << length << " mm, "
                   << (increment > 0.
                           ? "the largest prescribed displacement increment of a load step"
                           : "h: no prescribed displacement increment")
                   << ")\n";
      }
  }

  template <int dim>
  double
  SceneChecks<dim>::largest_dirichlet_increment() const
  {
    const BoundaryConditions::LoadSteps steps{
        view.load_stepping.end_time / view.load_stepping.n_steps, view.load_stepping.n_steps};
    double increment = 0.;
    for (const auto &condition : view.boundary_conditions)
      increment = std::max(increment, condition->largest_increment(view.boundary, steps));
    return Utilities::MPI::max(increment, view.communicator);
  }

  template <int dim>
  void
  SceneChecks<dim>::warn_of_boundary_conditions() const
  {
    for (const auto &condition : view.boundary_conditions)
      {
        condition->warn_if_not_ramped(view.boundary, view.pcout);
        condition->warn_if_held(
            view.boundary, view.newton_constraints, view.load_stepping.end_time, view.pcout);
      }
  }

  template class SceneChecks<2>;
  template class SceneChecks<3>;
} // namespace StabilizedLagrangian
