#include <deal.II/base/mpi.h>

#include <stabilized_lagrangian/contact/friction_law_check.h>
#include <stabilized_lagrangian/contact/stabilized_lagrangian.h>
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
        values.reinit(multiplier_cell(face.cell), face.face_no);
        // the face's nodes: λ_n's shape functions, ascending base index
        const std::vector<unsigned int> &local = multiplier_face_dofs(face.face_no);
        std::vector<unsigned int>        node_shapes;
        for (const auto &[base, node] : multiplier_nodes(
                 local, std::vector<types::global_dof_index>(local.begin(), local.end())))
          node_shapes.push_back(static_cast<unsigned int>(node[0]));
        const unsigned int n = node_shapes.size();
        FullMatrix<double> mass(n, n);
        for (unsigned int q = 0; q < contact_quadrature.size(); ++q)
          for (unsigned int p = 0; p < n; ++p)
            for (unsigned int r = 0; r < n; ++r)
              mass(p, r) += values.shape_value(node_shapes[p], q) *
                            values.shape_value(node_shapes[r], q) * values.JxW(q) *
                            radial_weight(values.quadrature_point(q));
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
    FaceEvaluator run_basis(*this, contact_quadrature), nodal_basis(*this, contact_quadrature);
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
    complementarity_choice = "Complementarity = automatic: " +
                             std::string(weighted_complementarity() ? "weighted" : "pointwise") +
                             " (" + choice.second + ")";
  }

  template <int dim>
  void
  ContactProblem<dim>::setup_nodal_conditions()
  {
    nodal = NodalConditions();
    // A constrained multiplier (a hanging node on Γc, a multiplier on a coarser
    // mesh) is no node of its own: its conditions would have to be split
    // among its masters, which the nodal conditions do not do.
    int constrained = 0;
    if (weighted_complementarity())
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
    if (!weighted_complementarity())
      return;
    if (constrained == 1)
      throw InputError(
          "Contact/Complementarity = weighted needs every multiplier node of the contact "
          "surface free, but this mesh and pair constrain some (hanging nodes on the contact "
          "surface from local refinement, or a pair with the multiplier on a coarser mesh). "
          "Refine the contact surface uniformly, choose another pair, or use "
          "Complementarity = pointwise.");
    if (dim == 3 && simplex_mesh() && fe_pair->multiplier_degree() > 1)
      throw InputError("Contact/Complementarity = weighted needs a multiplier whose basis "
                       "functions have a positive integral, but the quadratic multiplier on "
                       "the triangle faces of tetrahedra has zero integrals at the vertices. "
                       "Use a P1 multiplier (Finite element pair = P2/P1 or P1/P1) or "
                       "Complementarity = pointwise.");
    for (auto *vector : {&nodal.weights, &nodal.integrals, &nodal.status, &nodal.thresholds})
      vector->reinit(locally_owned, locally_relevant, mpi_communicator);

    // the nodes of this rank's contact faces, their Λ DoFs; the owned ones
    std::map<types::global_dof_index, std::vector<types::global_dof_index>> nodes, owned;
    for_each_contact_multiplier_face(
        [&](const std::vector<types::global_dof_index> &dofs, const unsigned int face) {
          const std::vector<unsigned int>     &local = multiplier_face_dofs(face);
          std::vector<types::global_dof_index> global(local.size());
          for (unsigned int a = 0; a < local.size(); ++a)
            global[a] = n_u + dofs[local[a]];
          for (const auto &[base, node] : multiplier_nodes(local, global))
            {
              const std::vector<types::global_dof_index> semi(node.begin() + 1, node.end());
              nodes[node[0]] = semi;
              if (locally_owned.is_element(node[0]))
                owned[node[0]] = semi;
            }
        });
    nodal.nodes.assign(nodes.begin(), nodes.end());
    nodal.owned_nodes.assign(owned.begin(), owned.end());

    if (!friction_law->threshold_depends_on_pressure())
      {
        TrilinosWrappers::MPI::Vector thresholds(locally_owned, mpi_communicator);
        for (const auto &node : nodal.owned_nodes)
          thresholds(node.first) = friction_law->threshold(0.);
        thresholds.compress(VectorOperation::insert);
        nodal.thresholds = thresholds;
      }
  }

  template <int dim>
  std::map<unsigned int, std::vector<types::global_dof_index>>
  ContactProblem<dim>::multiplier_nodes(const std::vector<unsigned int>            &local,
                                        const std::vector<types::global_dof_index> &global) const
  {
    // the components of one base DoF are one node: λ_n, then Λ_α
    std::map<unsigned int, std::vector<types::global_dof_index>> by_base;
    for (unsigned int a = 0; a < local.size(); ++a)
      {
        const auto [component, base] = fe_m->system_to_component_index(local[a]);
        auto &node                   = by_base[base];
        node.resize(fe_m->n_components());
        node[component] = global[a];
      }
    return by_base;
  }

  template <int dim>
  void
  ContactProblem<dim>::update_nodal_integrals(const bool pairing)
  {
    TrilinosWrappers::MPI::Vector weights(locally_owned, mpi_communicator);
    TrilinosWrappers::MPI::Vector integrals(locally_owned, mpi_communicator);
    FaceEvaluator                 evaluator(*this, contact_quadrature);
    PointRefresh                  what;
    what.pairing = pairing;
    for (const auto &face : contact_faces)
      {
        evaluator.reinit(face, ghosted_solution);
        const unsigned int n_m = evaluator.m_dofs.size();
        Vector<double>     face_weights(n_m), face_integrals(n_m);
        for (unsigned int q = 0; q < evaluator.n_points(); ++q)
          {
            ContactPointState<dim> &state = contact_states[face.first_point + q];
            ContactKinematics<dim>  k     = evaluator.kinematics(q);
            evaluate_point_state(state, k, what);
            const double             gap  = state.pairing.gap(k.position);
            const Tensor<1, dim - 1> slip = state.pairing.tangential_components(k.step_increment);
            for (unsigned int a = 0; a < n_m; ++a)
              {
                const unsigned int c = fe_m->system_to_component_index(evaluator.m_local[a]).first;
                const double       psi_w = evaluator.psi(a, q) * k.JxW;
                face_weights(a) += psi_w;
                face_integrals(a) += psi_w * (c == 0 ? gap : slip[c - 1]);
              }
          }
        weights.add(evaluator.m_dofs, face_weights);
        integrals.add(evaluator.m_dofs, face_integrals);
      }
    weights.compress(VectorOperation::add);
    integrals.compress(VectorOperation::add);
    nodal.weights   = weights;
    nodal.integrals = integrals;
  }

  template <int dim>
  unsigned int
  ContactProblem<dim>::update_nodal_statuses(const bool integrals_current)
  {
    if (!integrals_current)
      update_nodal_integrals(false);
    TrilinosWrappers::MPI::Vector status(locally_owned, mpi_communicator);
    unsigned int                  changes = 0;
    for (const auto &node : nodal.owned_nodes)
      {
        const types::global_dof_index j = node.first;
        if (nodal.weights(j) <= 0.)
          continue;
        // a gap within round-off of zero touches (status())
        const double gap        = nodal.integrals(j) / nodal.weights(j);
        const bool   in_contact = Contact::is_in_contact(
            Contact::augmented_pressure(ghosted_solution(j), status_gap(gap), chosen.r_n));
        changes += in_contact != (nodal.status(j) > 0.5);
        status(j) = in_contact ? 1. : 0.;
      }
    status.compress(VectorOperation::insert);
    nodal.status = status;
    return Utilities::MPI::sum(changes, mpi_communicator);
  }

  template <int dim>
  double
  ContactProblem<dim>::update_nodal_thresholds()
  {
    TrilinosWrappers::MPI::Vector thresholds(locally_owned, mpi_communicator);
    double                        max_change = 0., max_threshold = 0.;
    for (const auto &node : nodal.owned_nodes)
      {
        const types::global_dof_index j = node.first;
        const double s = friction_law->threshold(threshold_pressure(ghosted_solution(j)));
        max_change     = std::max(max_change, std::abs(s - nodal.thresholds(j)));
        max_threshold  = std::max(max_threshold, s);
        thresholds(j)  = s;
      }
    thresholds.compress(VectorOperation::insert);
    nodal.thresholds = thresholds;
    max_change       = Utilities::MPI::max(max_change, mpi_communicator);
    max_threshold    = Utilities::MPI::max(max_threshold, mpi_communicator);
    if (max_threshold == 0.)
      return max_change == 0. ? 0. : 1.;
    return max_change / max_threshold;
  }

  template <int dim>
  void
  ContactProblem<dim>::prepare_nodal_conditions(const PointRefresh &refresh)
  {
    update_nodal_integrals(refresh.pairing);
    if (refresh.status)
      update_nodal_statuses(true);
    if (refresh.threshold)
      update_nodal_thresholds();
    if (refresh.status || refresh.threshold)
      copy_nodal_states_to_points();
  }

  template <int dim>
  Contact::PointResponse<dim - 1>
  ContactProblem<dim>::nodal_response(const types::global_dof_index               node,
                                      const std::vector<types::global_dof_index> &semi_dofs) const
  {
    const double       weight = nodal.weights(node);
    const double       lambda = ghosted_solution(node);
    Tensor<1, dim - 1> semi, slip;
    for (unsigned int a = 0; a < semi_dofs.size(); ++a)
      {
        semi[a] = ghosted_solution(semi_dofs[a]);
        slip[a] = weight > 0. ? nodal.integrals(semi_dofs[a]) / weight : 0.;
      }
    return Contact::PointResponse<dim - 1>(
        lambda,
        weight > 0. ? nodal.integrals(node) / weight : 0.,
        semi,
        slip,
        nodal.status(node) > 0.5,
        nodal.thresholds(node),
        friction_law->has_friction(),
        chosen.r_n,
        chosen.r_t,
        loops.linearised(Loop::friction)
            ? friction_law->threshold_derivative(threshold_pressure(lambda))
            : 0.);
  }

  template <int dim>
  typename ContactProblem<dim>::NodeResponses
  ContactProblem<dim>::node_responses() const
  {
    NodeResponses responses;
    for (const auto &[node, semi_dofs] : nodal.nodes)
      responses.emplace(node, nodal_response(node, semi_dofs));
    return responses;
  }

  template <int dim>
  void
  ContactProblem<dim>::face_node_responses(const FaceEvaluator &evaluator,
                                           const NodeResponses &responses,
                                           FaceNodes           &nodes) const
  {
    std::map<unsigned int, const Contact::PointResponse<dim - 1> *> of_base;
    for (const auto &[base, node] : multiplier_nodes(evaluator.m_local, evaluator.m_dofs))
      of_base[base] = &responses.at(node[0]);
    nodes.of_multiplier.resize(evaluator.m_dofs.size());
    for (unsigned int a = 0; a < evaluator.m_dofs.size(); ++a)
      nodes.of_multiplier[a] =
          of_base.at(fe_m->system_to_component_index(evaluator.m_local[a]).second);
  }

  template <int dim>
  unsigned int
  ContactProblem<dim>::nearest_multiplier(const FaceEvaluator &evaluator,
                                          const unsigned int   q) const
  {
    double       largest = -1.;
    unsigned int nearest = 0;
    for (unsigned int a = 0; a < evaluator.m_dofs.size(); ++a)
      if (fe_m->system_to_component_index(evaluator.m_local[a]).first == 0)
        {
          const double psi = evaluator.psi(a, q);
          if (psi > largest)
            {
              largest = psi;
              nearest = a;
            }
        }
    return nearest;
  }

  template <int dim>
  const Contact::PointResponse<dim - 1> *
  ContactProblem<dim>::nearest_node(const FaceEvaluator &evaluator,
                                    const FaceNodes     &nodes,
                                    const unsigned int   q) const
  {
    if (!weighted_complementarity())
      return nullptr;
    return nodes.of_multiplier[nearest_multiplier(evaluator, q)];
  }

  template <int dim>
  void
  ContactProblem<dim>::copy_nodal_states_to_points()
  {
    // each point takes the status and threshold of its nearest node (the
    // largest ψ_j there): for the output, the counts and the error estimate
    FaceEvaluator evaluator(*this, contact_quadrature);
    for (const auto &face : contact_faces)
      {
        evaluator.reinit(face, ghosted_solution);
        for (unsigned int q = 0; q < evaluator.n_points(); ++q)
          {
            const types::global_dof_index nearest =
                evaluator.m_dofs[nearest_multiplier(evaluator, q)];
            ContactPointState<dim> &state = contact_states[face.first_point + q];
            state.in_contact              = nodal.status(nearest) > 0.5;
            state.friction_threshold      = nodal.thresholds(nearest);
          }
      }
  }

  template <int dim>
  std::vector<unsigned char>
  ContactProblem<dim>::nodal_statuses() const
  {
    std::vector<unsigned char> statuses;
    statuses.reserve(nodal.owned_nodes.size());
    for (const auto &[node, semi_dofs] : nodal.owned_nodes)
      statuses.push_back(static_cast<unsigned char>(nodal_response(node, semi_dofs).status()));
    return statuses;
  }

  template <int dim>
  void
  ContactProblem<dim>::weighted_contact_statistics(StepStatistics                 &stats,
                                                   Contact::FrictionLawCheck<dim> &check)
  {
    // the nodal quantities of the converged iterate (the last assembly saw the
    // iterate before the last update); a linearised threshold is s = μ λ_j of it
    update_nodal_integrals(false);
    if (loops.at_iterate().threshold)
      {
        update_nodal_thresholds();
        copy_nodal_states_to_points();
      }
    unsigned int counts[4] = {0, 0, 0, 0}; // all, in contact, stick, slip
    for (const auto &[node, semi_dofs] : nodal.owned_nodes)
      {
        if (nodal.weights(node) <= 0.)
          continue;
        const auto status = nodal_response(node, semi_dofs).status();
        ++counts[0];
        if (status == Contact::Status::open)
          continue;
        ++counts[1];
        ++counts[status == Contact::Status::stick ? 2 : 3];
      }
    // the forces of the multiplier field, ∫λ_n n + t_t over Γc
    double              normal_force = 0.;
    Tensor<1, dim>      normal_vector_force, tangential_force;
    FaceEvaluator       evaluator(*this, contact_quadrature);
    const NodeResponses responses = node_responses();
    FaceNodes           nodes;
    for (const auto &face : contact_faces)
      {
        evaluator.reinit(face, ghosted_solution);
        face_node_responses(evaluator, responses, nodes);
        for (unsigned int q = 0; q < evaluator.n_points(); ++q)
          {
            ContactPointState<dim> state = contact_states[face.first_point + q];
            ContactKinematics<dim> k     = evaluator.kinematics(q);
            evaluate_point_state(state, k, PointRefresh());
            Tensor<1, dim - 1> traction;
            for (unsigned int a = 0; a < evaluator.m_dofs.size(); ++a)
              {
                const unsigned int c = fe_m->system_to_component_index(evaluator.m_local[a]).first;
                if (c > 0)
                  traction[c - 1] +=
                      evaluator.psi(a, q) * nodes.of_multiplier[a]->multiplier_traction()[c - 1];
              }
            const double lambda = k.contact_pressure;
            if (lambda > negligible_pressure)
              {
                check.add_point(k.position - k.displacement,
                                traction.norm(),
                                friction_law->threshold(threshold_pressure(lambda)));
                active_set.push_back(k.position - k.displacement);
              }
            normal_force += k.JxW * lambda;
            normal_vector_force += k.JxW * lambda * state.pairing.normal;
            tangential_force += k.JxW * state.pairing.from_tangential_components(traction);
          }
      }
    stats.contact_points       = Utilities::MPI::sum(counts[0], mpi_communicator);
    stats.points_in_contact    = Utilities::MPI::sum(counts[1], mpi_communicator);
    stats.points_stick         = Utilities::MPI::sum(counts[2], mpi_communicator);
    stats.points_slip          = Utilities::MPI::sum(counts[3], mpi_communicator);
    stats.normal_force         = Utilities::MPI::sum(normal_force, mpi_communicator);
    const Tensor<1, dim> total = Utilities::MPI::sum(
        Tensor<1, dim>(normal_vector_force + tangential_force), mpi_communicator);
    const Tensor<1, dim> tangential = Utilities::MPI::sum(tangential_force, mpi_communicator);
    stats.tangential_force          = tangential.norm();
    for (unsigned int d = 0; d < dim; ++d)
      stats.contact_force[d] = total[d];
  }

  template <int dim>
  unsigned int
  ContactProblem<dim>::freeze_nodal_conditions(const std::function<bool(unsigned int)> &in_contact,
                                               const double                             threshold)
  {
    if (!weighted_complementarity())
      return 0;
    std::vector<double> values;
    for (unsigned int k = 0; k < nodal.owned_nodes.size(); ++k)
      {
        values.push_back(in_contact(k) ? 1. : 0.);
        values.push_back(threshold);
      }
    restore_nodal_states(values);
    copy_nodal_states_to_points();
    return nodal.owned_nodes.size();
  }

  template <int dim>
  std::vector<double>
  ContactProblem<dim>::owned_nodal_states() const
  {
    std::vector<double> values;
    for (const auto &node : nodal.owned_nodes)
      {
        values.push_back(nodal.status(node.first));
        values.push_back(nodal.thresholds(node.first));
      }
    return values;
  }

  template <int dim>
  void
  ContactProblem<dim>::restore_nodal_states(const std::vector<double> &values)
  {
    AssertThrow(values.size() == 2 * nodal.owned_nodes.size(),
                ExcMessage("the checkpoint's contact nodes do not fit this mesh"));
    if (!weighted_complementarity())
      return;
    TrilinosWrappers::MPI::Vector status(locally_owned, mpi_communicator);
    TrilinosWrappers::MPI::Vector thresholds(locally_owned, mpi_communicator);
    for (unsigned int k = 0; k < nodal.owned_nodes.size(); ++k)
      {
        status(nodal.owned_nodes[k].first)     = values[2 * k];
        thresholds(nodal.owned_nodes[k].first) = values[2 * k + 1];
      }
    status.compress(VectorOperation::insert);
    thresholds.compress(VectorOperation::insert);
    nodal.status     = status;
    nodal.thresholds = thresholds;
    update_nodal_integrals(false);
  }

  // Explicit instantiation of the members defined in this file (the class
  // itself is instantiated once, in contact_problem.cc).
#define SL_INSTANTIATE(dim)                                                                                        \
  template void ContactProblem<dim>::set_dual_multiplier_basis();                                                  \
  template std::map<std::pair<types::global_dof_index, types::global_dof_index>, double>                           \
                        ContactProblem<dim>::multiplier_mass() const;                                              \
  template void         ContactProblem<dim>::choose_complementarity();                                             \
  template void         ContactProblem<dim>::setup_nodal_conditions();                                             \
  template void         ContactProblem<dim>::update_nodal_integrals(bool);                                         \
  template unsigned int ContactProblem<dim>::update_nodal_statuses(bool);                                          \
  template double       ContactProblem<dim>::update_nodal_thresholds();                                            \
  template void         ContactProblem<dim>::prepare_nodal_conditions(const PointRefresh &);                       \
  template Contact::PointResponse<dim - 1> ContactProblem<dim>::nodal_response(                                    \
      types::global_dof_index, const std::vector<types::global_dof_index> &) const;                                \
  template typename ContactProblem<dim>::NodeResponses ContactProblem<dim>::node_responses()                       \
      const;                                                                                                       \
  template void ContactProblem<dim>::face_node_responses(                                                          \
      const FaceEvaluator &, const NodeResponses &, FaceNodes &) const;                                            \
  template std::map<unsigned int, std::vector<types::global_dof_index>>                                            \
                        ContactProblem<dim>::multiplier_nodes(const std::vector<unsigned int> &,                   \
                                        const std::vector<types::global_dof_index> &) const; \
  template void         ContactProblem<dim>::copy_nodal_states_to_points();                                        \
  template unsigned int ContactProblem<dim>::nearest_multiplier(const FaceEvaluator &,                             \
                                                                unsigned int) const;                               \
  template const Contact::PointResponse<dim - 1> *ContactProblem<dim>::nearest_node(                               \
      const FaceEvaluator &, const FaceNodes &, unsigned int) const;                                               \
  template std::vector<unsigned char> ContactProblem<dim>::nodal_statuses() const;                                 \
  template void                       ContactProblem<dim>::weighted_contact_statistics(                            \
      StepStatistics &, Contact::FrictionLawCheck<dim> &);                                   \
  template std::vector<double> ContactProblem<dim>::owned_nodal_states() const;                                    \
  template unsigned int        ContactProblem<dim>::freeze_nodal_conditions(                                       \
      const std::function<bool(unsigned int)> &, double);                                                   \
  template void ContactProblem<dim>::restore_nodal_states(const std::vector<double> &);

  SL_INSTANTIATE(2)
  SL_INSTANTIATE(3)
#undef SL_INSTANTIATE
} // namespace StabilizedLagrangian
