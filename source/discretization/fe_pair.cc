#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_trace.h>

#include <stabilized_lagrangian/discretization/fe_pair.h>

namespace StabilizedLagrangian
{
  namespace Discretization
  {
    /**
     * @brief Lagrange Q_k displacement with a continuous Lagrange multiplier of
     * degree m on the trace of the displacement mesh (FE_TraceQ).
     */
    template <int dim> class LagrangeTracePair : public FEPair<dim>
    {
    public:
      LagrangeTracePair(const unsigned int displacement_degree,
                        const unsigned int multiplier_degree)
          : u_degree(displacement_degree)
          , m_degree(multiplier_degree)
      {
      }

      std::unique_ptr<FiniteElement<dim>>
      displacement_element() const override
      {
        return std::make_unique<FESystem<dim>>(FE_Q<dim>(u_degree), dim);
      }

      std::unique_ptr<FiniteElement<dim>>
      multiplier_element(const unsigned int n_components) const override
      {
        return std::make_unique<FESystem<dim>>(FE_TraceQ<dim>(m_degree), n_components);
      }

      unsigned int
      displacement_degree() const override
      {
        return u_degree;
      }

      unsigned int
      multiplier_degree() const override
      {
        return m_degree;
      }

    private:
      const unsigned int u_degree, m_degree;
    };

    namespace
    {
      template <int dim>
      bool
      register_pairs()
      {
        return Registry<dim>::add(
            "Q1/P1",
            "Q1 displacement, continuous piecewise-linear multipliers on the displacement's "
            "boundary mesh",
            [](ParameterHandler &) {},
            [](const ParameterHandler &) -> std::unique_ptr<FEPair<dim>> {
              return std::make_unique<LagrangeTracePair<dim>>(1, 1);
            });
      }
      const bool registered_2d = register_pairs<2>();
      const bool registered_3d = register_pairs<3>();
    } // namespace
  }   // namespace Discretization
} // namespace StabilizedLagrangian
