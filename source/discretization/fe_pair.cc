#include <deal.II/fe/fe_face.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_trace.h>

#include <stabilized_lagrangian/discretization/fe_pair.h>

namespace StabilizedLagrangian
{
  namespace Discretization
  {
    /**
     * @brief Lagrange Q_k displacement with a Lagrange multiplier of degree m
     * on the faces of the displacement mesh: continuous across faces
     * (FE_TraceQ) or discontinuous, face by face (FE_FaceQ).
     */
    template <int dim> class LagrangeFacePair : public FEPair<dim>
    {
    public:
      LagrangeFacePair(const unsigned int displacement_degree,
                       const unsigned int multiplier_degree,
                       const bool         continuous_multiplier,
                       const bool         coarser_mesh = false,
                       const bool         dual_basis   = false)
          : FEPair<dim>(displacement_degree, multiplier_degree)
          , continuous(continuous_multiplier)
          , coarse(coarser_mesh)
          , dual(dual_basis)
      {
      }

      std::unique_ptr<FiniteElement<dim>>
      displacement_element() const override
      {
        return std::make_unique<FESystem<dim>>(FE_Q<dim>(this->u_degree), dim);
      }

      std::unique_ptr<FiniteElement<dim>>
      multiplier_element(const unsigned int n_components) const override
      {
        if (continuous)
          return std::make_unique<FESystem<dim>>(FE_TraceQ<dim>(this->m_degree), n_components);
        return std::make_unique<FESystem<dim>>(FE_FaceQ<dim>(this->m_degree), n_components);
      }

      bool
      multiplier_on_coarser_mesh() const override
      {
        return coarse;
      }

      bool
      dual_multiplier() const override
      {
        return dual;
      }

    private:
      const bool continuous, coarse, dual;
    };

    SL_REGISTER_PLUGIN_WITHOUT_PARAMETERS(
        FEPair,
        LagrangeFacePair,
        "Q1/P1",
        "Q1 displacement, continuous piecewise-linear multipliers on the displacement's boundary "
        "mesh (the seed's choice; inf-sup stable)",
        1,
        1,
        true);
    SL_REGISTER_PLUGIN_WITHOUT_PARAMETERS(
        FEPair,
        LagrangeFacePair,
        "Q2/P1",
        "Q2 displacement, continuous piecewise-linear multipliers on the displacement's boundary "
        "mesh (inf-sup stable)",
        2,
        1,
        true);
    SL_REGISTER_PLUGIN_WITHOUT_PARAMETERS(
        FEPair,
        LagrangeFacePair,
        "Q2/P2",
        "Q2 displacement, continuous piecewise-quadratic multipliers on the displacement's "
        "boundary mesh (inf-sup stable: the multiplier space is the displacement trace)",
        2,
        2,
        true);
    SL_REGISTER_PLUGIN_WITHOUT_PARAMETERS(
        FEPair,
        LagrangeFacePair,
        "Q1/P1 dual",
        "Q1 displacement, multipliers in the dual (biorthogonal) basis of the piecewise-linear "
        "ones on the displacement's boundary mesh: the multiplier mass matrix is diagonal, as in "
        "dual mortar methods (inf-sup stable). Needs Contact/Complementarity = weighted",
        1,
        1,
        true,
        false,
        true);
    SL_REGISTER_PLUGIN_WITHOUT_PARAMETERS(
        FEPair,
        LagrangeFacePair,
        "Q2/P2 dual",
        "Q2 displacement, multipliers in the dual basis of the piecewise-quadratic ones (built "
        "directly on the 3-node edges and 9-node faces, whose basis functions all have positive "
        "integrals; inf-sup stable). Needs Contact/Complementarity = weighted",
        2,
        2,
        true,
        false,
        true);
    SL_REGISTER_PLUGIN_WITHOUT_PARAMETERS(
        FEPair,
        LagrangeFacePair,
        "Q1/P1 coarse",
        "Q1 displacement, continuous piecewise-linear multipliers on the contact mesh coarsened "
        "once (mesh size 2h: the parents of the contact faces; inf-sup stable, fewer "
        "multipliers). Needs a contact boundary refined at least once and without hanging nodes",
        1,
        1,
        true,
        true);
    SL_REGISTER_PLUGIN_WITHOUT_PARAMETERS(
        FEPair,
        LagrangeFacePair,
        "Q1/P0",
        "Q1 displacement, multipliers constant on each boundary face: violates the inf-sup "
        "condition on the same mesh (the face-alternating multiplier is seen only at the ends of "
        "Γc, β_h → 0 under refinement), though the system stays invertible",
        1,
        0,
        false);
    SL_REGISTER_PLUGIN_WITHOUT_PARAMETERS(
        FEPair,
        LagrangeFacePair,
        "Q1/P2",
        "Q1 displacement, continuous piecewise-quadratic multipliers: richer than the "
        "displacement trace, violates the inf-sup condition (β_h = 0: the Newton system is "
        "singular where contact is active; see Linear solver/Null pivot detection)",
        1,
        2,
        true);

    /**
     * @brief Lagrange P_k displacement on triangles / tetrahedra with a
     * continuous P_m multiplier: the boundary DoFs of a P_m field of the whole
     * mesh, of which only those on Γc are kept (the other DoFs are numbered
     * last and never enter the system, as the skeleton DoFs of FE_TraceQ).
     */
    template <int dim> class LagrangeSimplexPair : public FEPair<dim>
    {
    public:
      LagrangeSimplexPair(const unsigned int displacement_degree,
                          const unsigned int multiplier_degree)
          : FEPair<dim>(displacement_degree, multiplier_degree)
      {
      }

      std::unique_ptr<FiniteElement<dim>>
      displacement_element() const override
      {
        return std::make_unique<FESystem<dim>>(FE_SimplexP<dim>(this->u_degree), dim);
      }

      std::unique_ptr<FiniteElement<dim>>
      multiplier_element(const unsigned int n_components) const override
      {
        return std::make_unique<FESystem<dim>>(FE_SimplexP<dim>(this->m_degree), n_components);
      }

      bool
      simplex() const override
      {
        return true;
      }
    };

    SL_REGISTER_PLUGIN_WITHOUT_PARAMETERS(
        FEPair,
        LagrangeSimplexPair,
        "P1/P1",
        "triangles / tetrahedra: P1 displacement, continuous piecewise-linear multipliers on its "
        "boundary mesh (the seed's element, §3; inf-sup stable: the multiplier space is the "
        "displacement trace)",
        1,
        1);
    SL_REGISTER_PLUGIN_WITHOUT_PARAMETERS(
        FEPair,
        LagrangeSimplexPair,
        "P2/P1",
        "triangles / tetrahedra: P2 displacement, continuous piecewise-linear multipliers "
        "(inf-sup stable)",
        2,
        1);
    SL_REGISTER_PLUGIN_WITHOUT_PARAMETERS(
        FEPair,
        LagrangeSimplexPair,
        "P2/P2",
        "triangles / tetrahedra: P2 displacement, continuous piecewise-quadratic multipliers "
        "(inf-sup stable: the multiplier space is the displacement trace)",
        2,
        2);
    SL_REGISTER_PLUGIN_WITHOUT_PARAMETERS(
        FEPair,
        LagrangeSimplexPair,
        "P1/P2",
        "triangles / tetrahedra: P1 displacement, continuous piecewise-quadratic multipliers: "
        "richer than the displacement trace, violates the inf-sup condition (β_h = 0)",
        1,
        2);
  } // namespace Discretization
} // namespace StabilizedLagrangian
