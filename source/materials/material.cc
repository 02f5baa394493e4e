#include <stabilized_lagrangian/materials/material.h>

namespace StabilizedLagrangian
{
  namespace Materials
  {
    template <int dim>
    void
    declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Material");
      Registry<dim>::declare_parameters(
          prm, "linear elastic", "Constitutive model of the deformable body.");
      prm.leave_subsection();
    }

    template <int dim>
    std::unique_ptr<Interface<dim>>
    create(ParameterHandler &prm)
    {
      prm.enter_subsection("Material");
      auto model = Registry<dim>::create(prm);
      prm.leave_subsection();
      return model;
    }

    template void
    declare_parameters<2>(ParameterHandler &);
    template void
    declare_parameters<3>(ParameterHandler &);
    template std::unique_ptr<Interface<2>>
    create<2>(ParameterHandler &);
    template std::unique_ptr<Interface<3>>
    create<3>(ParameterHandler &);
  } // namespace Materials
} // namespace StabilizedLagrangian
