#include <deal.II/base/mpi.h>

#include <stabilized_lagrangian/contact/weighted_conditions.h>

#include <cmath>
#include <limits>

// `Contact/Complementarity = weighted` (doc/formulation.md, "Weighted
// complementarity"): the contact and friction conditions hold once per
// multiplier node j, on the weighted gap g_j = ∫ψ_j g_n / D_j and slip
// Δs_j = ∫ψ_j Δs / D_j, D_j = ∫ψ_j, as in mortar methods; the displacement
// sees the multiplier field itself.

namespace StabilizedLagrangian
{
  template <int dim>
  std::map<unsigned int, std::vector<types::global_dof_index>>
  multiplier_nodes(const FiniteElement<dim>                   &fe_m,
                   const std::vector<unsigned int>            &local,
                   const std::vector<types::global_dof_index> &global)
  {
    // the components of one base DoF are one node: λ_n, then Λ_α
    std::map<unsigned int, std::vector<types::global_dof_index>> by_base;
    for (unsigned int a = 0; a < local.size(); ++a)
      {
        const auto [component, base] = fe_m.system_to_component_index(local[a]);
        auto &node                   = by_base[base];
        node.resize(fe_m.n_components());
        node[component] = global[a];
      }
    return by_base;
  }

  template <int dim>
  void
  WeightedConditions<dim>::setup()
  {
    const auto &data = this->data;
    for (auto *vector : {&weights, &integrals, &status, &thresholds})
      vector->reinit(data.locally_owned, data.locally_relevant, data.communicator);

    // the nodes of this rank's contact faces, their Λ DoFs; the owned ones
    std::map<types::global_dof_index, std::vector<types::global_dof_index>> all, owned;
    data.for_each_multiplier_face(
        [&](const std::vector<types::global_dof_index> &dofs, const unsigned int face) {
          const std::vector<unsigned int>     &local = data.spaces.multiplier_dofs_on_face[face];
          std::vector<types::global_dof_index> global(local.size());
          for (unsigned int a = 0; a < local.size(); ++a)
            global[a] = data.spaces.n_u + dofs[local[a]];
          for (const auto &[base, node] : multiplier_nodes(*data.spaces.fe_m, local, global))
            {
              const std::vector<types::global_dof_index> semi(node.begin() + 1, node.end());
              all[node[0]] = semi;
              if (data.locally_owned.is_element(node[0]))
                owned[node[0]] = semi;
            }
        });
    nodes.assign(all.begin(), all.end());
    owned_nodes.assign(owned.begin(), owned.end());

    if (!data.friction_law->threshold_depends_on_pressure())
      {
        TrilinosWrappers::MPI::Vector fixed(data.locally_owned, data.communicator);
        for (const auto &node : owned_nodes)
          fixed(node.first) = data.friction_law->threshold(0.);
        fixed.compress(VectorOperation::insert);
        thresholds = fixed;
      }
  }

  template <int dim>
  void
  WeightedConditions<dim>::update_integrals(const bool pairing)
  {
    const auto                   &data = this->data;
    const FiniteElement<dim>     &fe_m = *data.spaces.fe_m;
    TrilinosWrappers::MPI::Vector new_weights(data.locally_owned, data.communicator);
    TrilinosWrappers::MPI::Vector new_integrals(data.locally_owned, data.communicator);
    FaceEvaluator<dim>            evaluator(data.spaces, data.contact_quadrature);
    PointRefresh                  what;
    what.pairing = pairing;
    for (const auto &face : data.faces)
      {
        evaluator.reinit(face, data.ghosted_solution);
        const unsigned int n_m = evaluator.m_dofs.size();
        Vector<double>     face_weights(n_m), face_integrals(n_m);
        for (unsigned int q = 0; q < evaluator.n_points(); ++q)
          {
            ContactPointState<dim> &state = data.states[face.first_point + q];
            ContactKinematics<dim>  k     = evaluator.kinematics(q);
            data.law.evaluate_point_state(state, k, what);
            const double             gap  = state.pairing.gap(k.position);
            const Tensor<1, dim - 1> slip = state.pairing.tangential_components(k.step_increment);
            for (unsigned int a = 0; a < n_m; ++a)
              {
                const unsigned int c = fe_m.system_to_component_index(evaluator.m_local[a]).first;
                const double       psi_w = evaluator.psi(a, q) * k.JxW;
                face_weights(a) += psi_w;
                face_integrals(a) += psi_w * (c == 0 ? gap : slip[c - 1]);
              }
          }
        new_weights.add(evaluator.m_dofs, face_weights);
        new_integrals.add(evaluator.m_dofs, face_integrals);
      }
    new_weights.compress(VectorOperation::add);
    new_integrals.compress(VectorOperation::add);
    weights   = new_weights;
    integrals = new_integrals;
  }

  template <int dim>
  unsigned int
  WeightedConditions<dim>::update_nodal_statuses(const bool integrals_current)
  {
    const auto &data = this->data;
    if (!integrals_current)
      update_integrals(false);
    TrilinosWrappers::MPI::Vector new_status(data.locally_owned, data.communicator);
    unsigned int                  changes = 0;
    for (const auto &node : owned_nodes)
      {
        const types::global_dof_index j = node.first;
        if (weights(j) <= 0.)
          continue;
        // a gap within round-off of zero touches (status_gap())
        const double gap        = integrals(j) / weights(j);
        const bool   in_contact = Contact::is_in_contact(Contact::augmented_pressure(
            data.ghosted_solution(j), data.law.status_gap(gap), data.r_n));
        changes += in_contact != (status(j) > 0.5);
        new_status(j) = in_contact ? 1. : 0.;
      }
    new_status.compress(VectorOperation::insert);
    status = new_status;
    return Utilities::MPI::sum(changes, data.communicator);
  }

  template <int dim>
  double
  WeightedConditions<dim>::update_nodal_thresholds()
  {
    const auto                   &data = this->data;
    TrilinosWrappers::MPI::Vector new_thresholds(data.locally_owned, data.communicator);
    double                        max_change = 0., max_threshold = 0.;
    for (const auto &node : owned_nodes)
      {
        const types::global_dof_index j = node.first;
        const double                  s =
            data.friction_law->threshold(data.law.threshold_pressure(data.ghosted_solution(j)));
        max_change        = std::max(max_change, std::abs(s - thresholds(j)));
        max_threshold     = std::max(max_threshold, s);
        new_thresholds(j) = s;
      }
    new_thresholds.compress(VectorOperation::insert);
    thresholds    = new_thresholds;
    max_change    = Utilities::MPI::max(max_change, data.communicator);
    max_threshold = Utilities::MPI::max(max_threshold, data.communicator);
    if (max_threshold == 0.)
      return max_change == 0. ? 0. : 1.;
    return max_change / max_threshold;
  }

  template <int dim>
  unsigned int
  WeightedConditions<dim>::update_statuses()
  {
    const unsigned int changes = update_nodal_statuses(false);
    copy_states_to_points();
    return changes;
  }

  template <int dim>
  double
  WeightedConditions<dim>::update_thresholds()
  {
    const double change = update_nodal_thresholds();
    copy_states_to_points();
    return change;
  }

  template <int dim>
  std::vector<unsigned char>
  WeightedConditions<dim>::contact_statuses() const
  {
    std::vector<unsigned char> statuses;
    for (const auto &node : owned_nodes)
      statuses.push_back(status(node.first) > 0.5);
    return statuses;
  }

  template <int dim>
  std::vector<unsigned char>
  WeightedConditions<dim>::statuses()
  {
    std::vector<unsigned char> statuses;
    statuses.reserve(owned_nodes.size());
    for (const auto &[node, semi_dofs] : owned_nodes)
      statuses.push_back(static_cast<unsigned char>(nodal_response(node, semi_dofs).status()));
    return statuses;
  }

  template <int dim>
  double
  WeightedConditions<dim>::least_gap(const double)
  {
    // the nodes' weighted gaps ∫ψ_j g_n / ∫ψ_j: the nearest node closes
    update_integrals(false);
    double nearest = std::numeric_limits<double>::max();
    for (const auto &node : owned_nodes)
      if (weights(node.first) > 0.)
        nearest = std::min(nearest, integrals(node.first) / weights(node.first));
    return Utilities::MPI::min(nearest, this->data.communicator);
  }

  template <int dim>
  void
  WeightedConditions<dim>::close_nearest(const double, const double)
  {
    // the status test sees the approach gap as touching (status_gap())
    update_nodal_statuses(true);
    copy_states_to_points();
  }

  template <int dim>
  PointRefresh
  WeightedConditions<dim>::prepare_assembly(const PointRefresh &refresh)
  {
    // the nodes' statuses and thresholds come from the whole of their
    // supports, so what the iterate refreshes is refreshed first
    update_integrals(refresh.pairing);
    if (refresh.status)
      update_nodal_statuses(true);
    if (refresh.threshold)
      update_nodal_thresholds();
    if (refresh.status || refresh.threshold)
      copy_states_to_points();
    compute_responses();
    return PointRefresh();
  }

  template <int dim>
  void
  WeightedConditions<dim>::prepare_sampling()
  {
    compute_responses();
  }

  template <int dim>
  Contact::PointResponse<dim - 1>
  WeightedConditions<dim>::nodal_response(
      const types::global_dof_index               node,
      const std::vector<types::global_dof_index> &semi_dofs) const
  {
    const auto        &data   = this->data;
    const double       weight = weights(node);
    const double       lambda = data.ghosted_solution(node);
    Tensor<1, dim - 1> semi, slip;
    for (unsigned int a = 0; a < semi_dofs.size(); ++a)
      {
        semi[a] = data.ghosted_solution(semi_dofs[a]);
        slip[a] = weight > 0. ? integrals(semi_dofs[a]) / weight : 0.;
      }
    return Contact::PointResponse<dim - 1>(
        lambda,
        weight > 0. ? integrals(node) / weight : 0.,
        semi,
        slip,
        status(node) > 0.5,
        thresholds(node),
        data.friction_law->has_friction(),
        data.r_n,
        data.r_t,
        data.loops.linearised(Loop::friction)
            ? data.friction_law->threshold_derivative(data.law.threshold_pressure(lambda))
            : 0.);
  }

  template <int dim>
  void
  WeightedConditions<dim>::compute_responses()
  {
    responses.clear();
    for (const auto &[node, semi_dofs] : nodes)
      responses.emplace(node, nodal_response(node, semi_dofs));
  }

  template <int dim>
  void
  WeightedConditions<dim>::reinit_face(const FaceEvaluator<dim> &evaluator)
  {
    const FiniteElement<dim>                                       &fe_m = *this->data.spaces.fe_m;
    std::map<unsigned int, const Contact::PointResponse<dim - 1> *> of_base;
    for (const auto &[base, node] : multiplier_nodes(fe_m, evaluator.m_local, evaluator.m_dofs))
      of_base[base] = &responses.at(node[0]);
    face_nodes.resize(evaluator.m_dofs.size());
    for (unsigned int a = 0; a < evaluator.m_dofs.size(); ++a)
      face_nodes[a] = of_base.at(fe_m.system_to_component_index(evaluator.m_local[a]).second);
  }

  template <int dim>
  void
  WeightedConditions<dim>::add_point(internal::ContactFaceSystem<dim> &local,
                                     const ContactPointState<dim>     &state,
                                     const ContactKinematics<dim>     &k,
                                     const bool                        assemble_matrix,
                                     const bool                        linearise_geometry) const
  {
    local.add_weighted_residual(face_nodes, state.pairing.gap(k.position), k.JxW);
    if (assemble_matrix)
      local.add_weighted_jacobian(face_nodes, state.pairing, k.JxW, linearise_geometry);
  }

  template <int dim>
  unsigned int
  WeightedConditions<dim>::nearest_multiplier(const FaceEvaluator<dim> &evaluator,
                                              const unsigned int        q) const
  {
    const FiniteElement<dim> &fe_m    = *this->data.spaces.fe_m;
    double                    largest = -1.;
    unsigned int              nearest = 0;
    for (unsigned int a = 0; a < evaluator.m_dofs.size(); ++a)
      if (fe_m.system_to_component_index(evaluator.m_local[a]).first == 0)
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
  WeightedConditions<dim>::response_at(const FaceEvaluator<dim> &evaluator,
                                       const unsigned int        q) const
  {
    return face_nodes[nearest_multiplier(evaluator, q)];
  }

  template <int dim>
  void
  WeightedConditions<dim>::copy_states_to_points()
  {
    // each point takes the status and threshold of its nearest node (the
    // largest ψ_j there): for the output, the counts and the error estimate
    const auto        &data = this->data;
    FaceEvaluator<dim> evaluator(data.spaces, data.contact_quadrature);
    for (const auto &face : data.faces)
      {
        evaluator.reinit(face, data.ghosted_solution);
        for (unsigned int q = 0; q < evaluator.n_points(); ++q)
          {
            const types::global_dof_index nearest =
                evaluator.m_dofs[nearest_multiplier(evaluator, q)];
            ContactPointState<dim> &state = data.states[face.first_point + q];
            state.in_contact              = status(nearest) > 0.5;
            state.friction_threshold      = thresholds(nearest);
          }
      }
  }

  template <int dim>
  void
  WeightedConditions<dim>::statistics(StepStatistics                 &stats,
                                      Contact::FrictionLawCheck<dim> &check,
                                      std::vector<Point<dim>>        &active_set)
  {
    const auto &data = this->data;
    // the nodal quantities of the converged iterate (the last assembly saw the
    // iterate before the last update); a linearised threshold is s = μ λ_j of it
    update_integrals(false);
    if (data.loops.at_iterate().threshold)
      {
        update_nodal_thresholds();
        copy_states_to_points();
      }
    unsigned int counts[4] = {0, 0, 0, 0}; // all, in contact, stick, slip
    for (const auto &[node, semi_dofs] : owned_nodes)
      {
        if (weights(node) <= 0.)
          continue;
        const auto node_status = nodal_response(node, semi_dofs).status();
        ++counts[0];
        if (node_status == Contact::Status::open)
          continue;
        ++counts[1];
        ++counts[node_status == Contact::Status::stick ? 2 : 3];
      }
    // the forces of the multiplier field, ∫λ_n n + t_t over Γc
    const FiniteElement<dim> &fe_m         = *data.spaces.fe_m;
    double                    normal_force = 0.;
    Tensor<1, dim>            normal_vector_force, tangential_force;
    FaceEvaluator<dim>        evaluator(data.spaces, data.contact_quadrature);
    compute_responses();
    for (const auto &face : data.faces)
      {
        evaluator.reinit(face, data.ghosted_solution);
        reinit_face(evaluator);
        for (unsigned int q = 0; q < evaluator.n_points(); ++q)
          {
            ContactPointState<dim> state = data.states[face.first_point + q];
            ContactKinematics<dim> k     = evaluator.kinematics(q);
            data.law.evaluate_point_state(state, k, PointRefresh());
            Tensor<1, dim - 1> traction;
            for (unsigned int a = 0; a < evaluator.m_dofs.size(); ++a)
              {
                const unsigned int c = fe_m.system_to_component_index(evaluator.m_local[a]).first;
                if (c > 0)
                  traction[c - 1] +=
                      evaluator.psi(a, q) * face_nodes[a]->multiplier_traction()[c - 1];
              }
            const double lambda = k.contact_pressure;
            if (lambda > data.negligible_pressure)
              {
                check.add_point(k.position - k.displacement,
                                traction.norm(),
                                data.friction_law->threshold(data.law.threshold_pressure(lambda)));
                active_set.push_back(k.position - k.displacement);
              }
            normal_force += k.JxW * lambda;
            normal_vector_force += k.JxW * lambda * state.pairing.normal;
            tangential_force += k.JxW * state.pairing.from_tangential_components(traction);
          }
      }
    this->gather_totals(stats,
                        counts,
                        normal_force,
                        Tensor<1, dim>(normal_vector_force + tangential_force),
                        tangential_force);
  }

  template <int dim>
  void
  WeightedConditions<dim>::restore(const ContactConditions<dim> &copy)
  {
    // what an iterate changes; the nodes are the mesh's (setup()), and a step
    // cut keeps the mesh
    const auto &saved = dynamic_cast<const WeightedConditions<dim> &>(copy);
    Assert(saved.nodes == nodes, ExcMessage("a copy of the conditions on another mesh"));
    weights    = saved.weights;
    integrals  = saved.integrals;
    status     = saved.status;
    thresholds = saved.thresholds;
  }

  template <int dim>
  std::vector<double>
  WeightedConditions<dim>::owned_states() const
  {
    std::vector<double> values;
    for (const auto &node : owned_nodes)
      {
        values.push_back(status(node.first));
        values.push_back(thresholds(node.first));
      }
    return values;
  }

  template <int dim>
  void
  WeightedConditions<dim>::restore_states(const std::vector<double> &values)
  {
    AssertThrow(values.size() == 2 * owned_nodes.size(),
                ExcMessage("the checkpoint's contact nodes do not fit this mesh"));
    const auto                   &data = this->data;
    TrilinosWrappers::MPI::Vector new_status(data.locally_owned, data.communicator);
    TrilinosWrappers::MPI::Vector new_thresholds(data.locally_owned, data.communicator);
    for (unsigned int k = 0; k < owned_nodes.size(); ++k)
      {
        new_status(owned_nodes[k].first)     = values[2 * k];
        new_thresholds(owned_nodes[k].first) = values[2 * k + 1];
      }
    new_status.compress(VectorOperation::insert);
    new_thresholds.compress(VectorOperation::insert);
    status     = new_status;
    thresholds = new_thresholds;
    update_integrals(false);
  }

  template <int dim>
  unsigned int
  WeightedConditions<dim>::freeze(const std::function<bool(unsigned int)> &in_contact,
                                  const double                             threshold)
  {
    std::vector<double> values;
    for (unsigned int k = 0; k < owned_nodes.size(); ++k)
      {
        values.push_back(in_contact(k) ? 1. : 0.);
        values.push_back(threshold);
      }
    restore_states(values);
    copy_states_to_points();
    return owned_nodes.size();
  }

  template std::map<unsigned int, std::vector<types::global_dof_index>>
  multiplier_nodes(const FiniteElement<2> &,
                   const std::vector<unsigned int> &,
                   const std::vector<types::global_dof_index> &);
  template std::map<unsigned int, std::vector<types::global_dof_index>>
  multiplier_nodes(const FiniteElement<3> &,
                   const std::vector<unsigned int> &,
                   const std::vector<types::global_dof_index> &);
  template class WeightedConditions<2>;
  template class WeightedConditions<3>;
} // namespace StabilizedLagrangian
