#include <deal.II/fe/fe_values.h>

#include <stabilized_lagrangian/materials/body_response.h>

namespace StabilizedLagrangian
{
  namespace Materials
  {
    template <int dim>
    void
    BodyResponse<dim>::compute_volume_fields(const TrilinosWrappers::MPI::Vector &u) const
    {
      if (std::none_of(materials.begin(), materials.end(), [](const auto &body) {
            return body.modified_volume();
          }))
        return;
      FEValues<dim> centre_values(
          *fe_u, body_mesh.cell_gauss(1), update_gradients | update_JxW_values);
      FEValues<dim> cell_values(*fe_u, cell_quadrature, update_gradients | update_JxW_values);
      const FEValuesExtractors::Vector displacement(0);
      std::vector<Tensor<2, dim>>      gradients(cell_quadrature.size()), centre(1);
      const unsigned int               n_cells = dof_handler_u.get_triangulation().n_active_cells();
      centre_gradients.assign(n_cells, Tensor<2, dim>());
      kept_volume_coefficients.assign(n_cells, {});
      for (const auto &cell : dof_handler_u.active_cell_iterators())
        if (!cell->is_artificial())
          {
            const auto &body = body_of(cell);
            if (!body.modified_volume())
              continue;
            centre_values.reinit(cell);
            centre_values[displacement].get_function_gradients(u, centre);
            centre_gradients[cell->active_cell_index()] = centre[0];
            VolumeProjection<dim> projection            = volume_projection(body);
            if (body.volumetric == BodyMaterial<dim>::Volumetric::f_bar)
              projection.reinit(centre_values.get_quadrature().get_points(),
                                centre_values.get_JxW_values(),
                                centre);
            else
              {
                cell_values.reinit(cell);
                cell_values[displacement].get_function_gradients(u, gradients);
                projection.reinit(
                    cell_quadrature.get_points(), cell_values.get_JxW_values(), gradients);
              }
            kept_volume_coefficients[cell->active_cell_index()] = projection.coefficients();
          }
    }

    template class BodyResponse<2>;
    template class BodyResponse<3>;
  } // namespace Materials
} // namespace StabilizedLagrangian
