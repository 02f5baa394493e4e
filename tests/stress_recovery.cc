// The stress recovery of the pressure estimate (source/solver/stress_recovery.cc):
// a stress field in the fit's space (degree p + 1 along the face, p across
// it) is recovered exactly at any point of a boundary face, on a distorted
// mesh with hanging nodes, 2D and 3D, p = 1 and 2; one more degree across
// the face is not (the check that can fail); a patch at an edge of the
// body drops the degree and still recovers a linear field.

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_q1.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>

#include <stabilized_lagrangian/solver/stress_recovery.h>

#include "check_tools.h"

#include <cmath>
#include <functional>
#include <iostream>
#include <string>

using namespace StabilizedLagrangian;
using namespace CheckTools;

namespace
{
  /**
   * The largest error of the stress recovered on the faces at y = 0 (the
   * bottom, boundary id 2) of the unit square or cube against @p field: on
   * the faces at the body's edges with @p corner_only, else on the others.
   */
  template <int dim>
  double
  recovery_error(const unsigned int                               degree,
                 const std::function<double(const Point<dim> &)> &field,
                 const bool                                       corner_only)
  {
    Triangulation<dim> triangulation;
    GridGenerator::hyper_cube(triangulation, 0., 1., true);
    triangulation.refine_global(3);
    GridTools::distort_random(0.2, triangulation, true, 7);
    // hanging nodes on the bottom face: refine the cells near the origin
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->center().norm() < 0.4)
        cell->set_refine_flag();
    triangulation.execute_coarsening_and_refinement();

    FESystem<dim>   fe(FE_Q<dim>(degree), dim);
    DoFHandler<dim> dof_handler(triangulation);
    dof_handler.distribute_dofs(fe);
    // samples at the cells' Gauss points of order p (any points will do
    // for an exact field in the fit's space)
    const QGauss<dim>   points(degree);
    StressRecovery<dim> recovery(dof_handler, degree, [&](const auto &cell) {
      std::vector<std::pair<Point<dim>, Tensor<2, dim>>> samples;
      for (unsigned int q = 0; q < points.size(); ++q)
        {
          const Point<dim> x =
              StaticMappingQ1<dim>::mapping.transform_unit_to_real_cell(cell, points.point(q));
          Tensor<2, dim> stress;
          for (unsigned int i = 0; i < dim; ++i)
            for (unsigned int j = 0; j < dim; ++j)
              stress[i][j] = (1. + i + 2. * j) * field(x);
          samples.emplace_back(x, stress);
        }
      return samples;
    });

    double error = 0.;
    for (const auto &cell : dof_handler.active_cell_iterators())
      for (const unsigned int f : cell->face_indices())
        if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == 2)
          {
            // a cell with another boundary face lies at an edge of the body
            unsigned int n_boundary_faces = 0;
            for (const unsigned int g : cell->face_indices())
              n_boundary_faces += cell->face(g)->at_boundary() ? 1 : 0;
            if (corner_only != (n_boundary_faces > 1))
              continue;
            Tensor<1, dim> normal;
            normal[1] = -1.;
            std::vector<Point<dim>> at;
            for (const unsigned int v : cell->face(f)->vertex_indices())
              at.push_back(cell->face(f)->vertex(v));
            at.push_back(cell->face(f)->center());
            const auto recovered = recovery.at(cell, f, normal, at);
            for (unsigned int q = 0; q < at.size(); ++q)
              for (unsigned int i = 0; i < dim; ++i)
                for (unsigned int j = 0; j < dim; ++j)
                  error = std::max(error,
                                   std::abs(recovered[q][i][j] - (1. + i + 2. * j) * field(at[q])));
          }
    return error;
  }

  template <int dim>
  void
  check_dimension()
  {
    const std::string name = std::to_string(dim) + "D: ";
    // y is the normal, x (and z) tangential
    const auto p1 = [](const Point<dim> &x) {
      const double z = dim == 3 ? x[dim - 1] : 0.;
      return 3. + x[0] - 2. * x[1] + x[0] * x[0] - z * x[0] + z * z + x[0] * x[1] - z * x[1];
    };
    const auto p2 = [](const Point<dim> &x) {
      const double z = dim == 3 ? x[dim - 1] : 0.;
      return 1. + x[0] * x[0] * x[0] - z * z * x[0] + x[1] * x[1] - 2. * x[0] * x[0] * x[1] +
             x[1] * x[1] * z + z * z * z;
    };
    const auto across = [](const Point<dim> &x) { return x[1] * x[1]; };
    const auto linear = [](const Point<dim> &x) {
      return 1. + 2. * x[0] - x[1] + (dim == 3 ? 0.5 * x[dim - 1] : 0.);
    };
    check_below(recovery_error<dim>(1, p1, false),
                1e-10,
                name + "p = 1: quadratic along, linear across the face, recovered exactly");
    check_below(recovery_error<dim>(2, p2, false),
                1e-9,
                name + "p = 2: cubic along, quadratic across, recovered exactly");
    const double e = recovery_error<dim>(1, across, false);
    check(e > 1e-4, name + "p = 1: y^2 across the face is not in the fit's space, error", e);
    // three rings of samples at an edge: the normal equations' condition
    // number grows to about 1e7, so round-off reaches 1e-9 of the field
    check_below(recovery_error<dim>(1, linear, true),
                1e-8,
                name + "p = 1 at the body's edges: a linear field recovered");
  }
} // namespace

int
main()
{
  check_dimension<2>();
  check_dimension<3>();
  return summary();
}
