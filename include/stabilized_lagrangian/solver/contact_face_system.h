#pragma once

#include <deal.II/base/tensor.h>

#include <deal.II/fe/fe.h>
#include <deal.II/fe/fe_values.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <stabilized_lagrangian/contact/pairing.h>
#include <stabilized_lagrangian/contact/partner.h>
#include <stabilized_lagrangian/contact/stabilized_lagrangian.h>

#include <map>
#include <vector>

namespace StabilizedLagrangian
{
  namespace internal
  {
    using namespace dealii;

    /**
     * The local system of one contact face (doc/formulation.md, "Two deformable
     * bodies"): its unknowns are the slave cell's displacement DoFs, then the
     * DoFs of the partner's faces paired with the face's points (none for a
     * rigid obstacle; their shape functions enter with a minus sign: the gap
     * is (x¹ − x²(ξ))·n), then the face's multipliers.
     */
    template <int dim> struct ContactFaceSystem
    {
      ContactFaceSystem(const FiniteElement<dim> &fe_u, const FiniteElement<dim> &fe_m)
          : fe_m(fe_m)
          , n_u_cell(fe_u.n_dofs_per_cell())
          , u_component(n_u_cell)
      {
        for (unsigned int i = 0; i < n_u_cell; ++i)
          u_component[i] = fe_u.system_to_component_index(i).first;
      }

      /** Start a face: its cell's displacement DoFs and its multipliers. */
      void
      reinit(const std::vector<types::global_dof_index> &u_dofs,
             const std::vector<types::global_dof_index> &face_m_dofs,
             const std::vector<unsigned int>            &face_m_local)
      {
        dofs    = u_dofs;
        m_dofs  = face_m_dofs;
        m_local = face_m_local;
        n_m     = m_dofs.size();
        partner_position.clear();
        face_partner_dofs.clear();
        m_component.resize(n_m);
        for (unsigned int a = 0; a < n_m; ++a)
          m_component[a] = fe_m.system_to_component_index(m_local[a]).first;
        psi.resize(n_m);
      }

      /** Add the partner's DoFs of a point's pairing, once each. */
      void
      add_partner_dofs(const Contact::Partner<dim> &partner, const Contact::Pairing<dim> &pairing)
      {
        for (const auto dof : partner.pairing_dof_indices(pairing))
          if (partner_position.emplace(dof, n_u_cell + face_partner_dofs.size()).second)
            face_partner_dofs.push_back(dof);
      }

      /** Size the system once the partner's DoFs are known. */
      void
      finish_dofs()
      {
        n_d                  = n_u_cell + face_partner_dofs.size();
        const unsigned int n = n_d + n_m;
        matrix.reinit(n, n);
        rhs.reinit(n);
        length_weights.reinit(n);
        dofs.insert(dofs.end(), face_partner_dofs.begin(), face_partner_dofs.end());
        dofs.insert(dofs.end(), m_dofs.begin(), m_dofs.end());
        phi.resize(n_d);
        normal_shape.resize(n_d);
        tangential_shape.resize(n_d);
        slip_derivative.resize(n_d);
      }

      /**
       * The shape functions at point @p q: φ_j of the displacements (slave,
       * then partner), φ_j·n, t_α·φ_j, ∂Δs/∂u_j (plus (∂t_α/∂x φ_j)·Δu when
       * the tangents turn: @p step_increment given), and ψ of the multipliers.
       */
      void
      set_shapes(const FEFaceValues<dim>     &u_values,
                 const FEFaceValues<dim>     &m_values,
                 const unsigned int           q,
                 const Contact::Partner<dim> &partner,
                 const Contact::Pairing<dim> &pairing,
                 const Tensor<1, dim>        *step_increment)
      {
        for (unsigned int i = 0; i < n_d; ++i)
          phi[i] = Tensor<1, dim>();
        for (unsigned int i = 0; i < n_u_cell; ++i)
          phi[i][u_component[i]] = u_values.shape_value(i, q);
        partner.shape_values(pairing, partner_dofs, partner_components, partner_values);
        for (unsigned int r = 0; r < partner_dofs.size(); ++r)
          phi[partner_position[partner_dofs[r]]][partner_components[r]] -= partner_values[r];
        for (unsigned int i = 0; i < n_d; ++i)
          {
            normal_shape[i]     = phi[i] * pairing.normal;
            tangential_shape[i] = pairing.tangential_components(phi[i]);
            slip_derivative[i]  = tangential_shape[i];
            if (step_increment)
              for (unsigned int a = 0; a < dim - 1; ++a)
                slip_derivative[i][a] += (pairing.tangent_gradients[a] * phi[i]) * *step_increment;
          }
        for (unsigned int a = 0; a < n_m; ++a)
          psi[a] = m_values.shape_value(m_local[a], q);
      }

      /**
       * The point's residual: the slave's tractions do work against δu¹, the
       * partner's (opposite) against δu²(ξ); the multiplier rows of seed eq. (5).
       */
      void
      add_residual(const Contact::PointResponse<dim - 1> &point, const double w)
      {
        const double             normal_traction     = point.normal_traction();
        const Tensor<1, dim - 1> tangential_traction = point.tangential_traction();
        const double             pressure_residual   = point.pressure_residual();
        const Tensor<1, dim - 1> semi_residual       = point.semi_multiplier_residual();
        for (unsigned int i = 0; i < n_d; ++i)
          rhs(i) -=
              w * (normal_traction * normal_shape[i] + tangential_traction * tangential_shape[i]);
        for (unsigned int a = 0; a < n_m; ++a)
          {
            rhs(n_d + a) +=
                w * psi[a] *
                (m_component[a] == 0 ? pressure_residual : semi_residual[m_component[a] - 1]);
            length_weights(n_d + a) +=
                w * psi[a] * (m_component[a] == 0 ? 1. : point.semi_multiplier_weight());
          }
      }

      /** The point's Jacobian: matrix(i, j) = ∂ rhs(i) / ∂ x_j. */
      void
      add_jacobian(const Contact::PointResponse<dim - 1> &point,
                   const Contact::Pairing<dim>           &pairing,
                   const double                           w,
                   const bool                             linearise_geometry)
      {
        const double             normal_stiffness     = point.normal_stiffness();
        const Tensor<2, dim - 1> tangential_stiffness = point.tangential_stiffness();
        const double             normal_traction      = point.normal_traction();
        const Tensor<1, dim - 1> tangential_traction  = point.tangential_traction();
        for (unsigned int i = 0; i < n_d; ++i)
          for (unsigned int j = 0; j < n_d; ++j)
            {
              double value = normal_stiffness * normal_shape[i] * normal_shape[j] +
                             tangential_shape[i] * (tangential_stiffness * slip_derivative[j]);
              if (linearise_geometry)
                {
                  // the traction vector turns with n and t_α
                  value -= normal_traction * (phi[i] * (pairing.normal_gradient * phi[j]));
                  for (unsigned int a = 0; a < dim - 1; ++a)
                    value -=
                        tangential_traction[a] * (phi[i] * (pairing.tangent_gradients[a] * phi[j]));
                }
              matrix(i, j) += w * value;
            }
        add_multiplier_blocks(point, w);
      }

      /**
       * The displacement–multiplier couplings and the multiplier block. ∂T/∂λ_n
       * comes from the linearised threshold. The Λ rows keep their weight s/r_t
       * fixed at the iterate (doc/formulation.md): the derivative of the weight,
       * (s'/r_t)(Λ − P_B(ĝ)), vanishes at the solution and, large away from it
       * when r_t is small, only spoils the Newton steps.
       */
      void
      add_multiplier_blocks(const Contact::PointResponse<dim - 1> &point, const double w)
      {
        const double             pressure_coupling   = point.pressure_coupling();
        const Tensor<2, dim - 1> friction_coupling   = point.friction_coupling();
        const double             pressure_compliance = point.pressure_compliance();
        const Tensor<2, dim - 1> semi_block          = point.semi_multiplier_block();
        const Tensor<1, dim - 1> traction_slope = point.tangential_traction_pressure_derivative();
        for (unsigned int i = 0; i < n_d; ++i)
          for (unsigned int b = 0; b < n_m; ++b)
            {
              const unsigned int c = m_component[b];
              // u rows, multiplier columns
              matrix(i, n_d + b) += w * psi[b] *
                                    (c == 0 ? pressure_coupling * normal_shape[i] -
                                                  traction_slope * tangential_shape[i]
                                            : tangential_shape[i] * friction_coupling[c - 1]);
              // multiplier rows, u columns
              matrix(n_d + b, i) += w * psi[b] *
                                    (c == 0 ? pressure_coupling * normal_shape[i]
                                            : friction_coupling[c - 1] * slip_derivative[i]);
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
              matrix(n_d + a, n_d + b) += w * block * psi[a] * psi[b];
            }
      }

      /**
       * Weighted complementarity (doc/formulation.md, "Weighted
       * complementarity"): the point's share of the nodal conditions, the
       * multiplier field doing work against δu. @p nodes: the response of the
       * node of each of the face's multipliers (Contact::PointResponse on the
       * node's weighted gap and slip), @p gap: g_n at the point.
       */
      void
      add_weighted_residual(const std::vector<const Contact::PointResponse<dim - 1> *> &nodes,
                            const double                                                gap,
                            const double                                                w)
      {
        set_multiplier_tractions(nodes);
        for (unsigned int i = 0; i < n_d; ++i)
          rhs(i) -= w * (field_pressure * normal_shape[i] + field_traction * tangential_shape[i]);
        for (unsigned int a = 0; a < n_m; ++a)
          {
            const unsigned int c = m_component[a];
            rhs(n_d + a) += w * psi[a] *
                            (c == 0 ? nodes[a]->pressure_residual_at(gap)
                                    : nodes[a]->semi_multiplier_residual()[c - 1]);
            length_weights(n_d + a) +=
                w * psi[a] * (c == 0 ? 1. : nodes[a]->semi_multiplier_weight());
          }
      }

      /**
       * The Jacobian of add_weighted_residual(): the multiplier rows of a node
       * are nonlinear in its weighted slip only, whose derivative is the sum
       * of its points' ψ_j ∂Δs/∂u, so each point adds its share.
       */
      void
      add_weighted_jacobian(const std::vector<const Contact::PointResponse<dim - 1> *> &nodes,
                            const Contact::Pairing<dim>                                &pairing,
                            const double                                                w,
                            const bool linearise_geometry)
      {
        if (linearise_geometry)
          for (unsigned int i = 0; i < n_d; ++i)
            for (unsigned int j = 0; j < n_d; ++j)
              {
                double value = -field_pressure * (phi[i] * (pairing.normal_gradient * phi[j]));
                for (unsigned int a = 0; a < dim - 1; ++a)
                  value -= field_traction[a] * (phi[i] * (pairing.tangent_gradients[a] * phi[j]));
                matrix(i, j) += w * value;
              }
        for (unsigned int b = 0; b < n_m; ++b)
          {
            const unsigned int                     c    = m_component[b];
            const Contact::PointResponse<dim - 1> &node = *nodes[b];
            for (unsigned int i = 0; i < n_d; ++i)
              if (c == 0)
                {
                  matrix(i, n_d + b) +=
                      w * psi[b] *
                      (-normal_shape[i] -
                       node.multiplier_traction_pressure_derivative() * tangential_shape[i]);
                  matrix(n_d + b, i) += w * psi[b] * node.pressure_coupling() * normal_shape[i];
                }
              else
                {
                  matrix(i, n_d + b) +=
                      w * psi[b] * node.friction_factor() * tangential_shape[i][c - 1];
                  matrix(n_d + b, i) +=
                      w * psi[b] * (node.friction_coupling()[c - 1] * slip_derivative[i]);
                }
          }
        // the nodal blocks: a node's rows against its own multipliers
        for (unsigned int a = 0; a < n_m; ++a)
          for (unsigned int b = 0; b < n_m; ++b)
            if (nodes[a] == nodes[b])
              {
                const unsigned int ca = m_component[a], cb = m_component[b];
                double             block = 0.;
                if (ca == 0 && cb == 0)
                  block = nodes[a]->pressure_compliance();
                else if (ca > 0 && cb > 0)
                  block = nodes[a]->semi_multiplier_block()[ca - 1][cb - 1];
                matrix(n_d + a, n_d + b) += w * psi[a] * block;
              }
      }

      const FiniteElement<dim>                       &fe_m;
      const unsigned int                              n_u_cell;
      unsigned int                                    n_d = 0, n_m = 0;
      std::vector<unsigned int>                       u_component, m_component, m_local;
      std::vector<types::global_dof_index>            dofs, m_dofs, face_partner_dofs;
      std::map<types::global_dof_index, unsigned int> partner_position;
      FullMatrix<double>                              matrix;
      Vector<double>                                  rhs, length_weights;
      // at the current point
      std::vector<Tensor<1, dim>>          phi;
      std::vector<double>                  normal_shape, psi;
      std::vector<Tensor<1, dim - 1>>      tangential_shape, slip_derivative;
      std::vector<types::global_dof_index> partner_dofs;
      std::vector<unsigned int>            partner_components;
      std::vector<double>                  partner_values;
      /** the multiplier field's λ_n and tangential traction at the point (weighted) */
      double             field_pressure = 0.;
      Tensor<1, dim - 1> field_traction;

      void
      set_multiplier_tractions(const std::vector<const Contact::PointResponse<dim - 1> *> &nodes)
      {
        field_pressure = 0.;
        field_traction = Tensor<1, dim - 1>();
        for (unsigned int a = 0; a < n_m; ++a)
          if (m_component[a] == 0)
            field_pressure += psi[a] * nodes[a]->pressure();
          else
            field_traction[m_component[a] - 1] +=
                psi[a] * nodes[a]->multiplier_traction()[m_component[a] - 1];
      }
    };
  } // namespace internal
} // namespace StabilizedLagrangian
