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
        gap_shape.resize(n_d);
        tangential_shape.resize(n_d);
        slip_derivative.resize(n_d);
        normal_variation.resize(n_d);
        tangent_variation.resize(n_d);
        xi_variation.resize(n_d);
        partner_gradient.resize(n_d);
        partner_component.resize(n_d);
      }

      /**
       * The shape functions at point @p q: φ_j of the displacements (slave,
       * then partner), φ_j·n, t_α·φ_j, ∂Δs/∂u_j, and ψ of the multipliers.
       * When the pairing is linearised (@p step_increment given: the relative
       * Δs vector; @p offset: x¹ − x²(ξ), whose normal part is g_n), also how
       * n, t_α and, with a deformable master, ξ move with each DoF
       * (pairing_variations()), and ∂Δs/∂u_j and ∂g_n/∂u_j include them.
       */
      void
      set_shapes(const FEFaceValues<dim>     &u_values,
                 const Table<2, double>      &m_shapes,
                 const unsigned int           q,
                 const Contact::Partner<dim> &partner,
                 const Contact::Pairing<dim> &pairing,
                 const Tensor<1, dim>        *step_increment,
                 const Tensor<1, dim>        &offset = Tensor<1, dim>())
      {
        for (unsigned int i = 0; i < n_d; ++i)
          {
            phi[i]              = Tensor<1, dim>();
            partner_gradient[i] = Tensor<1, dim - 1>();
          }
        for (unsigned int i = 0; i < n_u_cell; ++i)
          phi[i][u_component[i]] = u_values.shape_value(i, q);
        partner.shape_values(pairing, partner_dofs, partner_components, partner_values);
        partner.shape_gradients(pairing, partner_gradients);
        for (unsigned int r = 0; r < partner_dofs.size(); ++r)
          {
            const unsigned int i = partner_position[partner_dofs[r]];
            phi[i][partner_components[r]] -= partner_values[r];
            partner_component[i] = partner_components[r];
            if (r < partner_gradients.size())
              partner_gradient[i] = partner_gradients[r];
          }
        for (unsigned int i = 0; i < n_d; ++i)
          {
            normal_shape[i]     = phi[i] * pairing.normal;
            gap_shape[i]        = normal_shape[i];
            tangential_shape[i] = pairing.tangential_components(phi[i]);
            slip_derivative[i]  = tangential_shape[i];
          }
        if (step_increment)
          pairing_variations(pairing, *step_increment, offset);
        for (unsigned int a = 0; a < n_m; ++a)
          psi[a] = m_shapes(a, q);
      }

      /**
       * The linearised pairing (doc/formulation.md, "Two deformable bodies"):
       * per DoF j, δn_j, δt_α,j and δξ_j, and the slip's convective terms.
       * A rigid obstacle: δn = ∂n/∂x φ_j, ξ does not count. A deformable
       * master: the closest-point condition (x¹ − x²(ξ))·τ_b = 0 gives
       * A δξ = τ·(δx¹ − N δu²) + (x¹ − x²)·(∂N δu²), A_ab = τ_a·τ_b −
       * (x¹ − x²)·x²,ab, where x¹ − x² = g n at an interior closest point;
       * then δτ_a = ∂_a N δu² + x²,ab δξ_b and δn = −m^ab (n·δτ_a) τ_b.
       * Where the closest point is held at the face's edge (ξ_a at 0 or 1:
       * a slave point beyond the master's end, or in the shadow of a convex
       * kink), that ξ_a stays there (δξ_a = 0, its condition dropped),
       * x¹ − x² has a tangential part, and the gap g_n = n·(x¹ − x²) moves
       * with n too: δg = n·(δx¹ − N δu²) + δn·(x¹ − x²).
       */
      void
      pairing_variations(const Contact::Pairing<dim> &pairing,
                         const Tensor<1, dim>        &slip_vector,
                         const Tensor<1, dim>        &offset)
      {
        const bool deformable = pairing.master_face >= 0;
        bool       held[dim - 1];
        for (unsigned int a = 0; a < dim - 1; ++a)
          held[a] = deformable && (pairing.master_reference_point[a] <= 0. ||
                                   pairing.master_reference_point[a] >= 1.);
        const auto         tangent_derivative = Contact::tangent_basis_derivative(pairing.normal);
        Tensor<2, dim - 1> metric, A;
        for (unsigned int a = 0; a < dim - 1; ++a)
          for (unsigned int b = 0; b < dim - 1; ++b)
            {
              metric[a][b] = pairing.surface_tangents[a] * pairing.surface_tangents[b];
              A[a][b]      = metric[a][b] - offset * pairing.surface_curvature[a][b];
              if (held[a] || held[b])
                A[a][b] = a == b ? 1. : 0.;
            }
        const Tensor<2, dim - 1> metric_inverse =
            deformable ? invert(metric) : Tensor<2, dim - 1>();
        const Tensor<2, dim - 1> A_inverse = deformable ? invert(A) : Tensor<2, dim - 1>();
        for (unsigned int j = 0; j < n_d; ++j)
          {
            const bool partner_dof = j >= n_u_cell;
            xi_variation[j]        = Tensor<1, dim - 1>();
            if (!deformable)
              normal_variation[j] = pairing.normal_gradient * phi[j];
            else
              {
                Tensor<1, dim - 1> rhs;
                for (unsigned int b = 0; b < dim - 1; ++b)
                  rhs[b] =
                      held[b]
                          ? 0.
                          : pairing.surface_tangents[b] * phi[j] +
                                (partner_dof ? partner_gradient[j][b] * offset[partner_component[j]]
                                             : 0.);
                xi_variation[j] = A_inverse * rhs;
                Tensor<1, dim> d_tau[dim - 1];
                for (unsigned int a = 0; a < dim - 1; ++a)
                  {
                    if (partner_dof)
                      d_tau[a][partner_component[j]] += partner_gradient[j][a];
                    for (unsigned int b = 0; b < dim - 1; ++b)
                      d_tau[a] += pairing.surface_curvature[a][b] * xi_variation[j][b];
                  }
                normal_variation[j] = Tensor<1, dim>();
                for (unsigned int a = 0; a < dim - 1; ++a)
                  for (unsigned int b = 0; b < dim - 1; ++b)
                    normal_variation[j] -= metric_inverse[a][b] * (pairing.normal * d_tau[a]) *
                                           pairing.surface_tangents[b];
                // (x¹ − x²) = g n at an interior closest point, and δn·n = 0
                gap_shape[j] = normal_shape[j] + normal_variation[j] * offset;
              }
            for (unsigned int a = 0; a < dim - 1; ++a)
              {
                tangent_variation[j][a] = deformable ? tangent_derivative[a] * normal_variation[j]
                                                     : pairing.tangent_gradients[a] * phi[j];
                slip_derivative[j][a] += tangent_variation[j][a] * slip_vector;
                if (deformable)
                  for (unsigned int b = 0; b < dim - 1; ++b)
                    slip_derivative[j][a] -=
                        (pairing.tangents[a] * pairing.increment_gradient[b]) * xi_variation[j][b];
              }
          }
      }

      /**
       * The traction @p normal_traction n + Σ @p tangential_traction_α t_α turns
       * with the pairing and, on a deformable master, the partner's test
       * functions −N_r(ξ) move with ξ: ∂(rhs_i)/∂u_j of those.
       */
      double
      geometric_stiffness(const double                 normal_traction,
                          const Tensor<1, dim - 1>    &tangential_traction,
                          const Contact::Pairing<dim> &pairing,
                          const unsigned int           i,
                          const unsigned int           j) const
      {
        double value = -normal_traction * (phi[i] * normal_variation[j]);
        for (unsigned int a = 0; a < dim - 1; ++a)
          value -= tangential_traction[a] * (phi[i] * tangent_variation[j][a]);
        if (i >= n_u_cell && pairing.master_face >= 0)
          {
            const Tensor<1, dim> traction = normal_traction * pairing.normal +
                                            pairing.from_tangential_components(tangential_traction);
            value += traction[partner_component[i]] * (partner_gradient[i] * xi_variation[j]);
          }
        return value;
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
            // ∫|ψ_a|: positive also where ψ_a changes sign (a quadratic or dual
            // basis function, whose ∫ψ_a 2πr vanishes on the axis of revolution)
            length_weights(n_d + a) +=
                w * std::abs(psi[a]) * (m_component[a] == 0 ? 1. : point.semi_multiplier_weight());
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
              double value = normal_stiffness * normal_shape[i] * gap_shape[j] +
                             tangential_shape[i] * (tangential_stiffness * slip_derivative[j]);
              if (linearise_geometry)
                value += geometric_stiffness(normal_traction, tangential_traction, pairing, i, j);
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
                                    (c == 0 ? pressure_coupling * gap_shape[i]
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
                w * std::abs(psi[a]) * (c == 0 ? 1. : nodes[a]->semi_multiplier_weight());
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
              matrix(i, j) +=
                  w * geometric_stiffness(field_pressure, field_traction, pairing, i, j);
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
                  matrix(n_d + b, i) += w * psi[b] * node.pressure_coupling() * gap_shape[i];
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
      std::vector<Tensor<1, dim>> phi;
      /** φ_j·n, and ∂g_n/∂u_j (φ_j·n, plus δn_j·(x¹ − x²) at a held closest point) */
      std::vector<double>                  normal_shape, gap_shape, psi;
      std::vector<Tensor<1, dim - 1>>      tangential_shape, slip_derivative;
      std::vector<types::global_dof_index> partner_dofs;
      std::vector<unsigned int>            partner_components;
      std::vector<double>                  partner_values;
      std::vector<Tensor<1, dim - 1>>      partner_gradients;
      /** the linearised pairing at the point: δn_j, δt_α,j, δξ_j; ∂N/∂ξ and component per DoF */
      std::vector<Tensor<1, dim>>                      normal_variation;
      std::vector<std::array<Tensor<1, dim>, dim - 1>> tangent_variation;
      std::vector<Tensor<1, dim - 1>>                  xi_variation, partner_gradient;
      std::vector<unsigned int>                        partner_component;
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
