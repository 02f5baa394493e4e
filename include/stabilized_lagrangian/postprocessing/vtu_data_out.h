#pragma once

#include <deal.II/base/mpi.h>
#include <deal.II/base/tensor.h>

#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_out_faces.h>
#include <deal.II/numerics/data_postprocessor.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

/**
 * @file
 * The pieces of deal.II's DataOut the VTU files of SolutionOutput are made
 * with: the stress of the cells, the faces of Γc, and the check that every
 * value fits a VTU file.
 */

namespace StabilizedLagrangian
{
  using namespace dealii;

  namespace internal
  {
    /**
     * @brief DataOut that can say which of its fields holds a value a VTU file
     * cannot carry: the patches store single precision, so a finite double
     * beyond 3.4e38 (an absurd stiffness times a strain) becomes inf, and a
     * NaN stays one. Nothing of the kind may reach a file (DESIGN.md §8).
     */
    template <int dim> class CheckedDataOut : public DataOut<dim>
    {
    public:
      /**
       * @brief The name of the first field with a value that is not finite in
       * the patches of any rank, or an empty string (collective).
       */
      std::string
      non_finite_field(const MPI_Comm communicator) const
      {
        const std::vector<std::string> names = this->get_dataset_names();
        std::string                    field;
        for (const auto &patch : this->get_patches())
          for (unsigned int row = 0; row < patch.data.n_rows() && field.empty(); ++row)
            for (unsigned int point = 0; point < patch.data.n_cols(); ++point)
              if (!std::isfinite(patch.data(row, point)))
                {
                  field = row < names.size() ? names[row] : "the vertex coordinates";
                  break;
                }
        for (const auto &name : Utilities::MPI::all_gather(communicator, field))
          if (!name.empty())
            return name;
        return "";
      }
    };

    /**
     * @brief The Cauchy stress tensor and the von Mises stress, averaged over the quadrature
     * points of each cell where the history variables live (plane strain:
     * the out-of-plane stress enters the von Mises stress).
     */
    template <int dim> class CellStressPostprocessor : public DataPostprocessor<dim>
    {
    public:
      /** @p hoop: an axisymmetric model, whose σ_θθ is a field of its own */
      CellStressPostprocessor(const std::vector<Tensor<2, 3>> &cell_stress, const bool hoop)
          : cell_stress(cell_stress)
          , hoop(hoop)
      {
      }

      void
      evaluate_vector_field(const DataPostprocessorInputs::Vector<dim> &inputs,
                            std::vector<Vector<double>>                &computed) const override
      {
        const Tensor<2, 3> &sigma =
            cell_stress[inputs.template get_cell<dim>()->active_cell_index()];
        const Tensor<2, 3> deviator  = sigma - trace(sigma) / 3. * unit_symmetric_tensor<3>();
        const double       von_mises = std::sqrt(1.5 * scalar_product(deviator, deviator));
        for (auto &values : computed)
          {
            for (unsigned int i = 0; i < dim; ++i)
              for (unsigned int j = 0; j < dim; ++j)
                values(i * dim + j) = sigma[i][j];
            values(dim * dim) = von_mises;
            if (hoop)
              values(dim * dim + 1) = sigma[2][2];
          }
      }

      std::vector<std::string>
      get_names() const override
      {
        std::vector<std::string> names(dim * dim, "stress_MPa");
        names.push_back("von_mises_stress_MPa");
        if (hoop)
          names.push_back("hoop_stress_MPa");
        return names;
      }

      std::vector<DataComponentInterpretation::DataComponentInterpretation>
      get_data_component_interpretation() const override
      {
        std::vector<DataComponentInterpretation::DataComponentInterpretation> kinds(
            dim * dim, DataComponentInterpretation::component_is_part_of_tensor);
        kinds.push_back(DataComponentInterpretation::component_is_scalar);
        if (hoop)
          kinds.push_back(DataComponentInterpretation::component_is_scalar);
        return kinds;
      }

      UpdateFlags
      get_needed_update_flags() const override
      {
        return update_default;
      }

    private:
      const std::vector<Tensor<2, 3>> &cell_stress;
      const bool                       hoop;
    };

    /** @brief The boundary faces of the locally owned cells that a predicate keeps (Γc). */
    template <int dim> class BoundaryFacesOut : public DataOutFaces<dim>
    {
    public:
      using FaceDescriptor = typename DataOutFaces<dim>::FaceDescriptor;
      using Keep =
          std::function<bool(const typename Triangulation<dim>::cell_iterator &, unsigned int)>;

      explicit BoundaryFacesOut(Keep keep)
          : DataOutFaces<dim>(true)
          , keep(std::move(keep))
      {
      }

      FaceDescriptor
      first_face() override
      {
        return first_kept(DataOutFaces<dim>::first_face());
      }

      FaceDescriptor
      next_face(const FaceDescriptor &face) override
      {
        return first_kept(DataOutFaces<dim>::next_face(face));
      }

    private:
      /** @p face or the first face after it that keep() accepts */
      FaceDescriptor
      first_kept(FaceDescriptor face)
      {
        while (face.first.state() == IteratorState::valid && !keep(face.first, face.second))
          face = DataOutFaces<dim>::next_face(face);
        return face;
      }

      const Keep keep;
    };
  } // namespace internal
} // namespace StabilizedLagrangian
