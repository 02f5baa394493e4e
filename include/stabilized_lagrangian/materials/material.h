#pragma once

#include <deal.II/base/array_view.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/utilities.h>

#include <stabilized_lagrangian/plugins.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

namespace StabilizedLagrangian
{
  namespace Materials
  {
    using namespace dealii;

    /**
     * @brief Copy of the components of @p t whose indices are all below
     * min(dim_from, dim_to), the others zero: the plane-strain (dim = 2)
     * quantities seen in 3D and back.
     */
    template <int dim_to, int rank, int dim_from>
    Tensor<rank, dim_to>
    common_block(const Tensor<rank, dim_from> &t)
    {
      constexpr int        dim = std::min(dim_from, dim_to);
      Tensor<rank, dim_to> result;
      for (unsigned int c = 0; c < Tensor<rank, dim>::n_independent_components; ++c)
        {
          const TableIndices<rank> indices = Tensor<rank, dim>::unrolled_to_component_indices(c);
          result[indices]                  = t[indices];
        }
      return result;
    }

    /**
     * @brief The 3D tensor whose leading dim×dim block is @p t, the other
     * components zero: the displacement gradient of plane strain (u_3 = 0,
     * ∂/∂x_3 = 0) seen in 3D.
     */
    template <int dim>
    Tensor<2, 3>
    embed_in_3d(const Tensor<2, dim> &t)
    {
      return common_block<3>(t);
    }

    /**
     * @brief The leading dim×dim (×dim×dim) block of a 3D tensor: in plane
     * strain the in-plane stress, and the tangent with the out-of-plane
     * components of the displacement gradient held at zero.
     */
    template <int dim, int rank>
    Tensor<rank, dim>
    in_plane_block(const Tensor<rank, 3> &t)
    {
      return common_block<dim>(t);
    }

    /**
     * @brief Response of a material at one quadrature point.
     *
     * The driver is written in the total Lagrangian form: the weak form is
     * ∫ P : ∇δu with P the first Piola–Kirchhoff stress and the consistent
     * tangent A = ∂P/∂F. For small-strain models P is the Cauchy stress and
     * A the elasticity tensor, which is the same weak form.
     */
    template <int dim> struct Response
    {
      /** First Piola–Kirchhoff stress (Cauchy stress in small strain). */
      Tensor<2, dim> stress;
      /** Consistent tangent ∂P/∂F (∂σ/∂∇u in small strain). */
      Tensor<4, dim> tangent;
      /** Cauchy stress in the out-of-plane direction (plane strain, dim = 2). */
      double out_of_plane_stress = 0.;
      /**
       * dim = 2: the out-of-plane (hoop) blocks of the 3D response, which the
       * axisymmetric weak form adds for the hoop stretch F₃₃ = 1 + u_r/r:
       * P₃₃, ∂P₃₃/∂F_kl, ∂P_kl/∂F₃₃ (k, l in the plane) and ∂P₃₃/∂F₃₃.
       */
      double         hoop_stress = 0.;
      Tensor<2, dim> hoop_row    = Tensor<2, dim>();
      Tensor<2, dim> hoop_column = Tensor<2, dim>();
      double         hoop_hoop   = 0.;
    };

    /**
     * @brief Thrown by a model when a state leaves its admissible range
     * (for instance J = det F ≤ 0); the load step is then cut.
     */
    class InadmissibleState : public std::runtime_error
    {
    public:
      using std::runtime_error::runtime_error;
    };

    /**
     * @brief Interface of the constitutive models.
     *
     * A model maps the displacement gradient (and its history variables at
     * the start of the load step) to stress and consistent tangent, and
     * writes the updated history variables; the driver commits them only
     * when a load step converges.
     */
    template <int dim> class Interface
    {
    public:
      virtual ~Interface() = default;

      /**
       * @brief Stress, tangent and updated history for a displacement gradient
       * in 3D (P and ∂P/∂F, or σ and ∂σ/∂∇u in small strain, 3 × 3). In plane
       * strain evaluate() calls it with the out-of-plane components zero; the
       * F-bar and mixed formulations call it with their modified gradient,
       * whose F̄₃₃ differs from 1 (include/stabilized_lagrangian/materials/f_bar.h).
       * @param grad_u displacement gradient ∇u (reference configuration)
       * @param old_history history variables at the start of the load step
       * @param new_history history variables for this state (size n_history())
       */
      virtual Response<3>
      evaluate_3d(const Tensor<2, 3>            &grad_u,
                  const ArrayView<const double> &old_history,
                  const ArrayView<double>       &new_history) const = 0;

      /**
       * @brief Stress, tangent and updated history for a displacement gradient
       * of dimension dim: in 2D plane strain (u₃ = 0, ∂/∂x₃ = 0), or with
       * @p hoop = u_r/r ≠ 0 the axisymmetric gradient (x₁ = r, x₃ = θ), whose
       * component 33 is the hoop strain.
       */
      Response<dim>
      evaluate(const Tensor<2, dim>          &grad_u,
               const ArrayView<const double> &old_history,
               const ArrayView<double>       &new_history,
               const double                   hoop = 0.) const
      {
        Tensor<2, 3> grad_u_3d = embed_in_3d(grad_u);
        if (dim == 2)
          grad_u_3d[2][2] = hoop;
        return in_plane_response(grad_u_3d, evaluate_3d(grad_u_3d, old_history, new_history));
      }

      /**
       * @brief The in-plane blocks of a 3D @p response at the 3D gradient
       * @p grad_u, and in plane strain its out-of-plane Cauchy stress.
       */
      Response<dim>
      in_plane_response(const Tensor<2, 3> &grad_u, const Response<3> &response) const
      {
        Response<dim> result;
        result.stress  = in_plane_block<dim>(response.stress);
        result.tangent = in_plane_block<dim>(response.tangent);
        if (dim == 2)
          {
            result.hoop_stress = response.stress[2][2];
            result.hoop_hoop   = response.tangent[2][2][2][2];
            for (unsigned int k = 0; k < dim; ++k)
              for (unsigned int l = 0; l < dim; ++l)
                {
                  result.hoop_row[k][l]    = response.tangent[2][2][k][l];
                  result.hoop_column[k][l] = response.tangent[k][l][2][2];
                }
          }
        if (dim == 2 && !is_finite_strain())
          result.out_of_plane_stress = response.stress[2][2];
        else if (dim == 2)
          {
            // σ = P Fᵀ / J
            Tensor<2, 3> F = grad_u;
            for (unsigned int d = 0; d < 3; ++d)
              F[d][d] += 1.;
            result.out_of_plane_stress = response.stress[2] * F[2] / determinant(F);
          }
        return result;
      }

      /** @brief Number of history variables per quadrature point (0: none). */
      virtual unsigned int
      n_history() const
      {
        return 0;
      }

      /**
       * @brief Values of the history variables before any loading (size
       * n_history()); zero unless a model says otherwise.
       */
      virtual void
      initial_history(const ArrayView<double> &history) const
      {
        for (double &h : history)
          h = 0.;
      }

      /**
       * @brief Names of the scalar fields derived from the history variables
       * that the output shows (for instance the equivalent plastic strain).
       */
      virtual std::vector<std::string>
      history_field_names() const
      {
        return {};
      }

      /** @brief Values of the fields named by history_field_names() for @p history. */
      virtual std::vector<double>
      history_fields(const ArrayView<const double> & /*history*/) const
      {
        return {};
      }

      /** @brief Whether the kinematics are finite strain (geometry must be updated). */
      virtual bool
      is_finite_strain() const = 0;

      /**
       * @brief Young's modulus of the linearised response, used to scale the
       * contact parameters and in the Hertz formulae.
       */
      virtual double
      youngs_modulus() const = 0;

      /** @brief Poisson's ratio of the linearised response. */
      virtual double
      poissons_ratio() const = 0;
    };

    /**
     * @brief Cauchy stress σ = P Fᵀ / J of a response (σ = P in small strain),
     * as a 3 x 3 tensor (plane strain: with the out-of-plane component).
     */
    template <int dim>
    Tensor<2, 3>
    cauchy_stress(const Tensor<2, dim> &grad_u,
                  const Response<dim>  &response,
                  const bool            finite_strain,
                  const double          hoop = 0.)
    {
      Tensor<2, dim> sigma = response.stress;
      if (finite_strain)
        {
          Tensor<2, dim> F = grad_u;
          for (unsigned int d = 0; d < dim; ++d)
            F[d][d] += 1.;
          // J = det F, with the hoop stretch 1 + u_r/r of an axisymmetric model
          sigma = response.stress * transpose(F) / (determinant(F) * (1. + hoop));
        }
      Tensor<2, 3> result;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          result[i][j] = sigma[i][j];
      if (dim == 2)
        result[2][2] = response.out_of_plane_stress;
      return result;
    }

    /** @brief The registry of material models for dimension @p dim. */
    template <int dim> using Registry = PluginRegistry<Interface<dim>>;

    /** @brief Number of material slots: `Material`, then `Material 2`, `Material 3`. */
    constexpr unsigned int n_material_slots = 3;

    /** @brief The subsection of material slot @p slot (0: `Material`). */
    inline std::string
    material_slot(const unsigned int slot)
    {
      return slot == 0 ? std::string("Material") : "Material " + std::to_string(slot + 1);
    }

    /** @brief Declare `Volumetric formulation` in the current (material slot) subsection. */
    inline void
    declare_volumetric_formulation(ParameterHandler &prm)
    {
      prm.declare_entry(
          "Volumetric formulation",
          "displacement",
          Patterns::Selection("displacement|F-bar|mixed"),
          "displacement: the model sees the displacement gradient at each quadrature point. "
          "F-bar: it sees the deformation gradient with its volume change taken at the cell's "
          "centre, F_bar = (J0/J)^(1/3) F (de Souza Neto, Peric, Dutko, Owen 1996; in small "
          "strain the B-bar of Hughes 1980: the trace of the strain taken at the centre), so that "
          "a cell keeps one volume constraint instead of one per quadrature point: Q1 "
          "quadrilaterals and hexahedra no longer lock when nu -> 0.5 or in plastic flow. "
          "mixed: the three-field displacement-pressure-dilatation formulation (Simo, Taylor, "
          "Pister 1985) with pressure and dilatation discontinuous, P0 with Q1 (the mean "
          "dilatation) and with P2 triangles and tetrahedra, P1 with Q2 (Q2/P1disc, inf-sup "
          "stable), condensed cell by cell so the system keeps the size of the displacement one: "
          "the model sees F_bar = (Pi J / J)^(1/3) F with Pi J the L2 projection of det F onto "
          "the pressure space (doc/formulation.md, \"Near incompressibility\"). Neither helps "
          "linear triangles and tetrahedra, whose gradient is already constant in the cell: "
          "mixed is refused there.");
    }

    /**
     * @brief Declare the `Material` subsection with every registered model, and
     * the slots `Material 2`, `Material 3` that give the bodies they list
     * (`Bodies`) a model of their own.
     */
    template <int dim>
    void
    declare_parameters(ParameterHandler &prm)
    {
      Registry<dim>::declare_parameters_in(
          prm,
          "Material",
          "linear elastic",
          "Constitutive model of the deformable bodies (of every body that no `Material 2`, "
          "`Material 3` slot lists).");
      prm.enter_subsection("Material");
      declare_volumetric_formulation(prm);
      prm.leave_subsection();
      for (unsigned int slot = 1; slot < n_material_slots; ++slot)
        {
          prm.enter_subsection(material_slot(slot));
          declare_volumetric_formulation(prm);
          prm.declare_entry("Bodies",
                            "",
                            Patterns::List(Patterns::Anything(), 0),
                            "Bodies of this model: names of the mesh's bodies (the physical "
                            "groups of dimension dim of a Gmsh mesh) or material ids. "
                            "Empty: the slot is unused.");
          Registry<dim>::declare_parameters(
              prm, "linear elastic", "Constitutive model of the bodies listed in `Bodies`.");
          prm.leave_subsection();
        }
    }

    /** @brief Build the model chosen in the `Material` subsection. */
    template <int dim>
    std::unique_ptr<Interface<dim>>
    create(ParameterHandler &prm)
    {
      return Registry<dim>::create_from(prm, "Material");
    }

    /** @brief A material slot in use: its model and the bodies it applies to. */
    template <int dim> struct BodyMaterial
    {
      std::string                     slot;   ///< its subsection, for messages
      std::vector<std::string>        bodies; ///< names or material ids; empty: the default
      std::unique_ptr<Interface<dim>> model;
      /** `Volumetric formulation`: the volume change each point keeps */
      enum class Volumetric
      {
        displacement, ///< its own
        f_bar,        ///< that of the cell's centre
        mixed         ///< the projection onto P_k(cell) (condensed three-field)
      } volumetric = Volumetric::displacement;
      /** @brief F-bar or mixed: the model sees a modified gradient. */
      bool
      modified_volume() const
      {
        return volumetric != Volumetric::displacement;
      }
      /** @brief Read `Volumetric formulation` in the current subsection. */
      void
      parse_volumetric(const ParameterHandler &prm)
      {
        const std::string choice = prm.get("Volumetric formulation");
        volumetric               = choice == "F-bar"   ? Volumetric::f_bar
                                   : choice == "mixed" ? Volumetric::mixed
                                                       : Volumetric::displacement;
      }
    };

    /** @brief The default model (`Material`) first, then every slot in use. */
    template <int dim>
    std::vector<BodyMaterial<dim>>
    create_all(ParameterHandler &prm)
    {
      std::vector<BodyMaterial<dim>> result;
      result.push_back(BodyMaterial<dim>{"Material", {}, create<dim>(prm)});
      prm.enter_subsection("Material");
      result.back().parse_volumetric(prm);
      prm.leave_subsection();
      for (unsigned int slot = 1; slot < n_material_slots; ++slot)
        {
          prm.enter_subsection(material_slot(slot));
          const auto bodies = Utilities::split_string_list(prm.get("Bodies"));
          if (!bodies.empty())
            {
              result.push_back(BodyMaterial<dim>{
                  material_slot(slot), bodies, Registry<dim>::create(prm, material_slot(slot))});
              result.back().parse_volumetric(prm);
            }
          prm.leave_subsection();
        }
      return result;
    }
  } // namespace Materials
} // namespace StabilizedLagrangian
