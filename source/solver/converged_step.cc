#include <deal.II/base/timer.h>

#include <stabilized_lagrangian/solver/contact_problem.h>

#include <algorithm>

namespace StabilizedLagrangian
{
  // What the problem does with a converged load step before the next one:
  // the state at the nodes of Γc is sampled once, the step's slip is
  // committed from it, and the output reads both.

  template <int dim>
  void
  ContactProblem<dim>::commit_converged_step(const unsigned int step, const double t)
  {
    TimerOutput::Scope              scope(timer, "output");
    std::vector<ContactSample<dim>> samples = sample_contact_surface();
    cumulative_slip.commit(step, samples);
    output_results(step, t, samples);
  }

  template <int dim>
  std::vector<ContactSample<dim>>
  ContactProblem<dim>::sample_contact_surface()
  {
    update_partner_configuration();
    // The nodes of the contact faces: the Gauss-Lobatto points of the larger
    // of the two degrees (the vertices for Q1/P1, also the midsides for
    // quadratic pairs; on triangle faces the vertices only: see face_nodes())
    const Quadrature<dim - 1> node_quadrature = face_nodes(
        (dim == 3 && simplex_mesh())
            ? 1u
            : std::max({fe_pair->displacement_degree(), fe_pair->multiplier_degree(), 1u}));
    FaceEvaluator evaluator(spaces, node_quadrature, false);
    evaluator.use_nodal_coefficients();
    conditions->prepare_sampling();
    std::vector<ContactSample<dim>> samples;
    for (const auto &face : contact_faces)
      {
        evaluator.reinit(face, ghosted_solution);
        conditions->reinit_face(evaluator);
        for (unsigned int q = 0; q < node_quadrature.size(); ++q)
          {
            ContactKinematics<dim> k = evaluator.kinematics(q);
            // with weighted complementarity, the tractions and status of the
            // point's nearest node
            const Contact::PointResponse<dim - 1> *node = conditions->response_at(evaluator, q);
            // the state of the converged iterate, evaluated afresh at the point
            ContactPointState<dim> state;
            evaluate_point_state(state, k, PointRefresh{true, true, true});
            const double gap = state.pairing.gap(k.position);
            samples.push_back({face.cell,
                               face.face_no,
                               evaluator.u_values->quadrature_point(q),
                               state,
                               k,
                               node ? *node : point_response(state, k),
                               gap,
                               Tensor<1, dim>(),
                               0.});
          }
      }
    return samples;
  }

  template void
  ContactProblem<2>::commit_converged_step(unsigned int, double);
  template void
  ContactProblem<3>::commit_converged_step(unsigned int, double);
  template std::vector<ContactSample<2>>
  ContactProblem<2>::sample_contact_surface();
  template std::vector<ContactSample<3>>
  ContactProblem<3>::sample_contact_surface();
} // namespace StabilizedLagrangian
