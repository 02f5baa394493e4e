#include <deal.II/base/mpi.h>

#include <stabilized_lagrangian/contact/friction_law_check.h>
#include <stabilized_lagrangian/contact/stabilized_lagrangian.h>
#include <stabilized_lagrangian/contact/weighted_conditions.h>
#include <stabilized_lagrangian/solver/contact_problem.h>

#include <cmath>
#include <string>
#include <utility>

// `Contact/Complementarity = weighted` (doc/formulation.md, "Weighted
// complementarity"): the contact and friction conditions hold once per
// multiplier node j, on the weighted gap g_j = ∫ψ_j g_n / D_j and slip
// Δs_j = ∫ψ_j Δs / D_j, D_j = ∫ψ_j, as in mortar methods; the displacement
// sees the multiplier field itself.

namespace StabilizedLagrangian
{
  template <int dim>
  void
  ContactProblem<dim>::set_dual_multiplier_basis()
  {
    // A = D M⁻¹ on each face, M_pr = ∫_F φ_p φ_r, D_pp = ∫_F φ_p = Σ_r M_pr,
    // on the reference face (the multiplier lives there): then
    // ∫_F ψ_p φ_r = D_pp δ_pr (Wohlmuth 2000; Popp, Gitterle, Gee, Wall 2010).
    // M with the contact quadrature (Gauss, degree + 1 points: exact for
    // φ_p φ_r J on plane faces), so that the assembled ∫ψ_j φ_k is diagonal
    // also on curved faces; on segmented faces the segments' rule is exact
    // where the face is plane.
    if (!fe_pair->dual_multiplier())
      return;
    // (axisymmetric: M and D with the weight 2πr of the model's measure)
    FEFaceValues<dim> values(
        *fe_m, contact_quadrature, update_values | update_JxW_values | update_quadrature_points);
    for (auto &face : contact_faces)
      {
        values.reinit(spaces.multiplier_cell(face.cell), face.face_no);
        // the face's nodes: λ_n's shape functions, ascending base index
        const std::vector<unsigned int> &local = spaces.multiplier_face_dofs(face.face_no);
        std::vector<unsigned int>        node_shapes;
        for (const auto &[base, node] : multiplier_nodes(
                 *fe_m, local, std::vector<types::global_dof_index>(local.begin(), local.end())))
          node_shapes.push_back(static_cast<unsigned int>(node[0]));
        const unsigned int n = node_shapes.size();
        FullMatrix<double> mass(n, n);
        for (unsigned int q = 0; q < contact_quadrature.size(); ++q)
          for (unsigned int p = 0; p < n; ++p)
            for (unsigned int r = 0; r < n; ++r)
              mass(p, r) += values.shape_value(node_shapes[p], q) *
                            values.shape_value(node_shapes[r], q) * values.JxW(q) *
                            spaces.radial_weight(values.quadrature_point(q));
        Vector<double> row_sums(n);
        for (unsigned int p = 0; p < n; ++p)
          for (unsigned int r = 0; r < n; ++r)
            row_sums(p) += mass(p, r);
        auto dual = std::make_shared<FullMatrix<double>>(n, n);
        dual->invert(mass);
        for (unsigned int p = 0; p < n; ++p)
          for (unsigned int r = 0; r < n; ++r)
            (*dual)(p, r) *= row_sums(p);
        face.dual_basis = dual;
      }
  }

  template <int dim>
  std::map<std::pair<types::global_dof_index, types::global_dof_index>, double>
  ContactProblem<dim>::multiplier_mass() const
  {
    std::map<std::pair<types::global_dof_index, types::global_dof_index>, double> mass;
    FaceEvaluator run_basis(spaces, contact_quadrature), nodal_basis(spaces, contact_quadrature);
    nodal_basis.use_nodal_coefficients();
    for (const auto &face : contact_faces)
      {
        run_basis.reinit(face, ghosted_solution);
        nodal_basis.reinit(face, ghosted_solution);
        for (unsigned int q = 0; q < run_basis.n_points(); ++q)
          for (unsigned int a = 0; a < run_basis.m_dofs.size(); ++a)
            for (unsigned int b = 0; b < run_basis.m_dofs.size(); ++b)
              if (fe_m->system_to_component_index(run_basis.m_local[a]).first == 0 &&
                  fe_m->system_to_component_index(run_basis.m_local[b]).first == 0)
                mass[{run_basis.m_dofs[a], run_basis.m_dofs[b]}] +=
                    run_basis.psi(a, q) * nodal_basis.psi(b, q) * run_basis.kinematics(q).JxW;
      }
    return mass;
  }

  template <int dim>
  void
  ContactProblem<dim>::choose_complementarity()
  {
    if (!contact_parameters.complementarity_automatic)
      return;
    const bool two_bodies =
        !contact_parameters.master_ids.empty() || !contact_parameters.master_names.empty();
    // Local refinement of a 3D contact surface puts hanging nodes on it in a
    // later cycle; the conditions are chosen once for all cycles.
    const bool local_refinement_3d =
        dim == 3 && adaptive_refinement.cycles > 0 &&
        adaptive_refinement.criterion != Parameters::AdaptiveRefinement::Criterion::uniform;
    using Conditions = Parameters::Complementarity;
    std::pair<Conditions, std::string> choice{Conditions::weighted, "two deformable bodies"};
    if (fe_pair->dual_multiplier())
      choice = {Conditions::weighted, "a dual pair: its conditions hold node by node"};
    else if (!two_bodies)
      choice = {Conditions::pointwise, "a rigid obstacle: the seed's formulation"};
    else if (!contact_zones.empty())
      choice = {Conditions::pointwise, "contact zones, built for the pointwise conditions"};
    else if (local_refinement_3d)
      choice = {Conditions::pointwise,
                "adaptive refinement of a 3D contact surface makes hanging nodes"};
    chosen.complementarity = choice.first;
    complementarity_choice =
        "Complementarity = automatic: " +
        std::string(chosen.weighted_complementarity() ? "weighted" : "pointwise") + " (" +
        choice.second + ")";
  }

  template <int dim>
  void
  ContactProblem<dim>::setup_contact_conditions()
  {
    // A constrained multiplier (a hanging node on Γc, a multiplier on a coarser
    // mesh) is no node of its own: its conditions would have to be split
    // among its masters, which the nodal conditions do not do.
    int constrained = 0;
    if (chosen.weighted_complementarity())
      for (const auto index : locally_relevant)
        if (index >= n_u && hanging_constraints.is_constrained(index))
          constrained = 1;
    constrained = Utilities::MPI::max(constrained, mpi_communicator);
    if (constrained == 1 && contact_parameters.complementarity_automatic &&
        !fe_pair->dual_multiplier())
      {
        chosen.complementarity = Parameters::Complementarity::pointwise;
        complementarity_choice = "Complementarity = automatic: pointwise (constrained multiplier "
                                 "nodes on the contact surface: hanging nodes or a coarser "
                                 "multiplier mesh)";
        constrained            = 0;
      }
    if (!complementarity_choice.empty())
      {
        pcout << complementarity_choice << "\n";
        complementarity_choice.clear();
      }
    if (chosen.weighted_complementarity() && constrained == 1)
      throw InputError(
          "Contact/Complementarity = weighted needs every multiplier node of the contact "
          "surface free, but this mesh and pair constrain some (hanging nodes on the contact "
          "surface from local refinement, or a pair with the multiplier on a coarser mesh). "
          "Refine the contact surface uniformly, choose another pair, or use "
          "Complementarity = pointwise.");
    if (chosen.weighted_complementarity() && dim == 3 && body_mesh.simplex() &&
        fe_pair->multiplier_degree() > 1)
      throw InputError("Contact/Complementarity = weighted needs a multiplier whose basis "
                       "functions have a positive integral, but the quadratic multiplier on "
                       "the triangle faces of tetrahedra has zero integrals at the vertices. "
                       "Use a P1 multiplier (Finite element pair = P2/P1 or P1/P1) or "
                       "Complementarity = pointwise.");
    conditions = make_contact_conditions(chosen.weighted_complementarity(), conditions_data());
    conditions->setup();
  }

  template <int dim>
  ContactConditionsData<dim>
  ContactProblem<dim>::conditions_data()
  {
    return ContactConditionsData<dim>{
        spaces,
        contact_quadrature,
        contact_faces,
        contact_states,
        ghosted_solution,
        locally_owned,
        locally_relevant,
        mpi_communicator,
        law,
        contact_zones.default_law(),
        chosen.r_n,
        chosen.r_t,
        loops,
        negligible_pressure,
        [this]() { return static_cast<unsigned int>(contact_zones.size()); },
        [this](const auto &f) { spaces.for_each_contact_multiplier_face(f); }};
  }

  template <int dim>
  unsigned int
  ContactProblem<dim>::freeze_nodal_conditions(const std::function<bool(unsigned int)> &in_contact,
                                               const double                             threshold)
  {
    return conditions->freeze(in_contact, threshold);
  }

  // Explicit instantiation of the members defined in this file (the class
  // itself is instantiated once, in contact_problem.cc).
#define SL_INSTANTIATE(dim)                                                              \
  template void ContactProblem<dim>::set_dual_multiplier_basis();                        \
  template std::map<std::pair<types::global_dof_index, types::global_dof_index>, double> \
                                      ContactProblem<dim>::multiplier_mass() const;      \
  template void                       ContactProblem<dim>::choose_complementarity();     \
  template void                       ContactProblem<dim>::setup_contact_conditions();   \
  template ContactConditionsData<dim> ContactProblem<dim>::conditions_data();            \
  template unsigned int               ContactProblem<dim>::freeze_nodal_conditions(      \
      const std::function<bool(unsigned int)> &, double);

  SL_INSTANTIATE(2)
  SL_INSTANTIATE(3)
#undef SL_INSTANTIATE
} // namespace StabilizedLagrangian
