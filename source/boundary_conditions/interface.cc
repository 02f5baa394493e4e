#include <deal.II/base/utilities.h>

#include <stabilized_lagrangian/boundary_conditions/interface.h>

#include <algorithm>

namespace StabilizedLagrangian
{
  namespace BoundaryConditions
  {
    template <int dim>
    Interface<dim>::Interface(const std::string &section)
        : path(section)
    {
    }

    template <int dim>
    const std::string &
    Interface<dim>::section() const
    {
      return path;
    }

    template <int dim>
    bool
    Interface<dim>::used() const
    {
      return true;
    }

    template <int dim>
    bool
    Interface<dim>::at_one_vertex() const
    {
      return false;
    }

    template <int dim>
    void
    Interface<dim>::resolve_boundaries(const BoundaryResolver &)
    {
    }

    template <int dim>
    std::vector<types::boundary_id>
    Interface<dim>::boundaries() const
    {
      return {};
    }

    template <int dim>
    void
    Interface<dim>::find_dofs(const Problem<dim> &, const VertexDoFs<dim> &)
    {
    }

    template <int dim>
    void
    Interface<dim>::find_linked_dofs(const Problem<dim> &,
                                     const std::vector<std::unique_ptr<Interface<dim>>> &,
                                     IndexSet &)
    {
    }

    template <int dim>
    void
    Interface<dim>::add_homogeneous_constraints(const Problem<dim> &,
                                                AffineConstraints<double> &) const
    {
    }

    template <int dim>
    void
    Interface<dim>::add_linked_constraints(const Problem<dim> &, AffineConstraints<double> &) const
    {
    }

    template <int dim>
    std::optional<IndexSet>
    Interface<dim>::linked_boundary_dofs(const Problem<dim> &, const unsigned int) const
    {
      return std::nullopt;
    }

    template <int dim>
    void
    Interface<dim>::check_prescribed_vertex(const Problem<dim> &, const Interface<dim> &) const
    {
    }

    template <int dim>
    void
    Interface<dim>::add_prescribed_values(const Problem<dim> &,
                                          const double,
                                          std::map<types::global_dof_index, double> &) const
    {
    }

    template <int dim>
    double
    Interface<dim>::largest_increment(const Problem<dim> &, const LoadSteps &) const
    {
      return 0.;
    }

    template <int dim>
    void
    Interface<dim>::warn_if_not_ramped(const Problem<dim> &, const ConditionalOStream &) const
    {
    }

    template <int dim>
    void
    Interface<dim>::warn_if_held(const Problem<dim> &,
                                 const AffineConstraints<double> &,
                                 double,
                                 const ConditionalOStream &) const
    {
    }

    template <int dim>
    std::optional<IndexSet>
    Interface<dim>::prescribed_boundary_dofs(const Problem<dim> &, const unsigned int) const
    {
      return std::nullopt;
    }

    template <int dim>
    std::optional<types::global_dof_index>
    Interface<dim>::prescribed_point_dof(const unsigned int) const
    {
      return std::nullopt;
    }

    template <int dim>
    void
    Interface<dim>::add_statistics_columns(StatisticsWriter::Supports &) const
    {
    }

    template <int dim>
    void
    Interface<dim>::add_statistics(const Problem<dim> &,
                                   const ReactionInputs<dim> &,
                                   StepStatistics &) const
    {
    }

    template <int dim>
    void
    Interface<dim>::hold_components(const types::boundary_id, std::vector<bool> &) const
    {
    }

    template <int dim>
    bool
    Interface<dim>::acts_on_faces_of(const types::boundary_id) const
    {
      return false;
    }

    template <int dim>
    void
    Interface<dim>::assemble_face(const Problem<dim> &, const FaceSystem<dim> &) const
    {
    }

    template <int dim>
    void
    Interface<dim>::check_finite(const MPI_Comm) const
    {
    }

    template <int dim>
    void
    Interface<dim>::assemble_global(const Problem<dim> &,
                                    const AffineConstraints<double> &,
                                    TrilinosWrappers::MPI::Vector &,
                                    TrilinosWrappers::MPI::Vector &) const
    {
    }

    template <int dim>
    void
    Interface<dim>::add_supported_boundaries(std::vector<types::boundary_id> &) const
    {
    }

    template <int dim>
    void
    Interface<dim>::add_reactions(const Problem<dim> &,
                                  const ReactionInputs<dim> &,
                                  const std::vector<types::boundary_id> &,
                                  std::vector<Tensor<1, dim>> &,
                                  IndexSet &) const
    {
    }

    template <int dim>
    void
    Interface<dim>::add_supports(std::vector<Support<dim>> &) const
    {
    }

    template <int dim>
    void
    Interface<dim>::add_boundary_load(const Problem<dim> &,
                                      const types::boundary_id,
                                      const Point<dim> &,
                                      const Tensor<1, dim> &,
                                      Vector<double> &) const
    {
    }

    template <int dim>
    OnBoundary<dim>::OnBoundary(const ParameterHandler &prm,
                                const std::string      &section,
                                const Role              role)
        : Interface<dim>(section)
        , role(role)
    {
      // the condition's boundary, or nothing where it is unused (-1)
      const std::string value = Utilities::trim(prm.get("Boundary id"));
      if (value == "-1")
        return;
      const auto id = Parameters::boundary_id_or_name(value, section + "/Boundary id");
      boundary_id   = id.value_or(0);
      boundary_name = id ? "" : value;
      is_used       = true;
    }

    template <int dim>
    bool
    OnBoundary<dim>::used() const
    {
      return is_used;
    }

    template <int dim>
    void
    OnBoundary<dim>::resolve_boundaries(const BoundaryResolver &resolve)
    {
      if (!boundary_name.empty())
        boundary_id = resolve(boundary_name, this->section() + "/Boundary id");
    }

    template <int dim>
    std::vector<types::boundary_id>
    OnBoundary<dim>::boundaries() const
    {
      return {boundary_id};
    }

    template <int dim>
    bool
    OnBoundary<dim>::acts_on_faces_of(const types::boundary_id id) const
    {
      return (role == Role::load || role == Role::elastic_support) && id == boundary_id;
    }

    template <int dim>
    void
    OnBoundary<dim>::add_supported_boundaries(std::vector<types::boundary_id> &ids) const
    {
      if ((role == Role::support || role == Role::elastic_support) &&
          std::find(ids.begin(), ids.end(), boundary_id) == ids.end())
        ids.push_back(boundary_id);
    }

    template <int dim>
    void
    OnBoundary<dim>::declare_boundary(ParameterHandler &prm, const std::string &what)
    {
      prm.declare_entry("Boundary id",
                        "-1",
                        Patterns::Anything(),
                        "Boundary " + what +
                            ": its id, or the name of a boundary of the mesh (a Gmsh "
                            "physical group); -1: unused.");
    }

    template <int dim>
    std::optional<Point<dim>>
    parse_point(const ParameterHandler &prm,
                const std::string      &section,
                const std::string      &entry,
                const std::string      &what)
    {
      const std::string text = Utilities::trim(prm.get(entry));
      if (text.empty())
        return std::nullopt;
      Point<dim> point;
      try
        {
          const auto values = Utilities::string_to_double(Utilities::split_string_list(text));
          if (values.size() != dim)
            throw std::invalid_argument("count");
          for (unsigned int d = 0; d < dim; ++d)
            point[d] = values[d];
        }
      catch (...)
        {
          throw InputError(section + "/" + entry + " = '" + text + "': " + std::to_string(dim) +
                           " comma-separated coordinates (mm) of " + what + ".");
        }
      return point;
    }

    std::vector<std::string>
    kinds()
    {
      return Registry<2>::names();
    }

    template <int dim>
    void
    declare_parameters(ParameterHandler &prm, const Parameters::ConditionSections &sections)
    {
      prm.enter_subsection("Boundary conditions");
      for (const auto &kind : kinds())
        if (const auto names = sections.conditions.find(kind); names != sections.conditions.end())
          for (const auto &name : names->second)
            if (!prm.subsection_path_exists({kind + " " + name}))
              {
                prm.enter_subsection(kind + " " + name);
                Registry<dim>::declare_parameters_here(kind, prm);
                prm.leave_subsection();
              }
      prm.leave_subsection();
    }

    template <int dim>
    std::vector<std::unique_ptr<Interface<dim>>>
    create(ParameterHandler &prm, const Parameters::ConditionSections &sections)
    {
      std::vector<std::unique_ptr<Interface<dim>>> conditions;
      prm.enter_subsection("Boundary conditions");
      for (const auto &kind : kinds())
        if (const auto names = sections.conditions.find(kind); names != sections.conditions.end())
          for (const auto &name : names->second)
            {
              prm.enter_subsection(kind + " " + name);
              auto condition =
                  Registry<dim>::create_here(kind, prm, "Boundary conditions/" + kind + " " + name);
              prm.leave_subsection();
              if (condition)
                conditions.push_back(std::move(condition));
            }
      prm.leave_subsection();
      std::stable_partition(conditions.begin(), conditions.end(), [](const auto &condition) {
        return !condition->at_one_vertex();
      });
      return conditions;
    }

#define SL_INSTANTIATE(dim)                                                                                             \
  template class Interface<dim>;                                                                                        \
  template class OnBoundary<dim>;                                                                                       \
  template std::optional<Point<dim>> parse_point<dim>(                                                                  \
      const ParameterHandler &, const std::string &, const std::string &, const std::string &);                         \
  template void                                         declare_parameters<dim>(ParameterHandler &,                     \
                                        const Parameters::ConditionSections &); \
  template std::vector<std::unique_ptr<Interface<dim>>> create<dim>(                                                    \
      ParameterHandler &, const Parameters::ConditionSections &);

    SL_INSTANTIATE(2)
    SL_INSTANTIATE(3)
#undef SL_INSTANTIATE
  } // namespace BoundaryConditions
} // namespace StabilizedLagrangian
