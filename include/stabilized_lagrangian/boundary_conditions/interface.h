#pragma once

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/base/tensor.h>

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe.h>
#include <deal.II/fe/fe_values.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <stabilized_lagrangian/parameters.h>
#include <stabilized_lagrangian/plugins.h>
#include <stabilized_lagrangian/postprocessing/statistics.h>

#include <array>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace StabilizedLagrangian
{
  /**
   * The boundary conditions: each kind a plug-in, `Boundary conditions/<Kind>
   * <name>` in the `.prm` file, any number of each. The problem holds a list
   * of them and asks each for its part of the constraints, the residual and
   * the Jacobian, the reactions and the checks; it never asks which kind one is.
   */
  namespace BoundaryConditions
  {
    using namespace dealii;

    /**
     * @brief What a boundary condition reads of the problem: the displacement's
     * space, the partition and the load path's time; a read-only view of the
     * problem's members, built where a condition is asked.
     */
    template <int dim> struct Problem
    {
      const DoFHandler<dim>    &dof_handler; ///< the displacement's
      const FiniteElement<dim> &fe;          ///< the displacement's
      const MPI_Comm            communicator;
      /** the owned DoFs of the monolithic numbering (displacements, multipliers, ...) */
      const IndexSet &locally_owned;
      const IndexSet &locally_owned_u; ///< the owned displacement DoFs
      const bool      axisymmetric;
      const double    time; ///< of the load path

      /**
       * @brief The measure of the model at @p x: 2πr in an axisymmetric model
       * (integrals over the solid of revolution), 1 otherwise.
       */
      double
      radial_weight(const Point<dim> &x) const
      {
        return axisymmetric ? 2. * numbers::PI * x[0] : 1.;
      }
    };

    /** @brief The load path's steps: @p n_steps of length @p step from t = 0. */
    struct LoadSteps
    {
      double       step;
      unsigned int n_steps;
    };

    /** @brief The DoFs of component @p c on boundary @p id (those this rank sees). */
    template <int dim>
    IndexSet
    boundary_component_dofs(const DoFHandler<dim>   &dof_handler,
                            const types::boundary_id id,
                            const unsigned int       c)
    {
      ComponentMask component(dim, false);
      component.set(c, true);
      return DoFTools::extract_boundary_dofs(dof_handler, component, {id});
    }

    /**
     * @brief Call @p f on each vertex of the faces of boundary @p id of the
     * locally owned cells (a vertex once per face).
     */
    template <int dim, typename Function>
    void
    for_each_boundary_vertex(const Triangulation<dim> &triangulation,
                             const types::boundary_id  id,
                             const Function           &f)
    {
      for (const auto &cell : triangulation.active_cell_iterators())
        if (cell->is_locally_owned())
          for (const unsigned int face : cell->face_indices())
            if (cell->face(face)->at_boundary() && cell->face(face)->boundary_id() == id)
              for (const unsigned int v : cell->face(face)->vertex_indices())
                f(cell->face(face)->vertex(v));
    }

    /** @brief The id of the boundary a mesh names @p name; errors name @p entry. */
    using BoundaryResolver =
        std::function<types::boundary_id(const std::string &name, const std::string &entry)>;

    /**
     * @brief The DoFs of the vertex at a point, per component; errors name the
     * condition's subsection (SystemConstraints::vertex_dofs).
     */
    template <int dim>
    using VertexDoFs = std::function<std::array<types::global_dof_index, dim>(
        const Point<dim> &point, const std::string &section)>;

    /** @brief One boundary face of a locally owned cell in the Newton assembly. */
    template <int dim> struct FaceSystem
    {
      const typename DoFHandler<dim>::active_cell_iterator &cell;
      const unsigned int                                    face_no;
      /** the cell's displacement coefficients at the iterate */
      const std::vector<double> &coefficients;
      FEFaceValues<dim>         &face_values;
      FullMatrix<double>        &cell_matrix;
      Vector<double>            &cell_rhs; ///< the residual's, −(the forces' work)
      const bool                 assemble_matrix;
    };

    /** @brief What the reactions are computed from: the step's converged forces. */
    template <int dim> struct ReactionInputs
    {
      const TrilinosWrappers::MPI::Vector &internal_force;
      const TrilinosWrappers::MPI::Vector &external_force;
      const TrilinosWrappers::MPI::Vector &contact_residual;
      /** the displacement, ghosted (computed at the first call) */
      const std::function<const TrilinosWrappers::MPI::Vector &()> displacement;
      /** the face quadrature of the displacement's space */
      const Quadrature<dim - 1> &face_quadrature;
    };

    /**
     * @brief Where a support holds the body: on a boundary's vertices or at one
     * point, in the components @p held (setup_checks.cc, the rigid-motion check).
     */
    template <int dim> struct Support
    {
      std::optional<types::boundary_id> boundary; ///< none: at @p point
      Point<dim>                        point;
      std::vector<bool>                 held;
    };

    /**
     * @brief Interface of the boundary conditions. Each kind overrides the
     * parts it takes in; the defaults take none.
     */
    template <int dim> class Interface
    {
    public:
      /** @param section its subsection's path, `Boundary conditions/Neumann top`, for messages */
      explicit Interface(const std::string &section);

      virtual ~Interface() = default;

      /** @brief The subsection's path, for messages. */
      const std::string &
      section() const;

      /** @brief False for a condition its subsection leaves unused: the problem drops it. */
      virtual bool
      used() const;

      /**
       * @brief Whether it acts at one vertex. Such conditions come after those
       * on boundaries (create()): at its vertex, what it prescribes replaces what
       * a boundary's condition prescribes in the same component.
       */
      virtual bool
      at_one_vertex() const;

      /** @brief Resolve the boundary given by a mesh's name to its id. */
      virtual void
      resolve_boundaries(const BoundaryResolver &resolve);

      /** @brief The boundaries it acts on, which the mesh must have. */
      virtual std::vector<types::boundary_id>
      boundaries() const;

      /** @brief Find its DoFs on a new mesh (the vertices of point conditions). */
      virtual void
      find_dofs(const Problem<dim> &problem, const VertexDoFs<dim> &vertex_dofs);

      /**
       * @brief Collective, on a new mesh before the constraints are built:
       * find the DoFs its constraints link others to (add_linked_constraints()),
       * add them to @p relevant (every rank couples to them), and refuse DoFs
       * that the @p conditions (the problem's list, this one among them)
       * prescribe or link already.
       */
      virtual void
      find_linked_dofs(const Problem<dim>                                 &problem,
                       const std::vector<std::unique_ptr<Interface<dim>>> &conditions,
                       IndexSet                                           &relevant);

      /** @brief Add its homogeneous constraints (the Newton correction's) to @p constraints. */
      virtual void
      add_homogeneous_constraints(const Problem<dim>        &problem,
                                  AffineConstraints<double> &constraints) const;

      /**
       * @brief Add its constraints that link DoFs to others, u_i = Σ_k C_ik
       * u_{r_k}, to @p constraints, after every condition's homogeneous ones
       * (a DoF constrained already keeps its constraint).
       */
      virtual void
      add_linked_constraints(const Problem<dim>        &problem,
                             AffineConstraints<double> &constraints) const;

      /**
       * @brief The DoFs of component @p c of its boundary that its constraints
       * link to others (add_linked_constraints()); none if it links none.
       */
      virtual std::optional<IndexSet>
      linked_boundary_dofs(const Problem<dim> &problem, unsigned int c) const;

      /**
       * @brief Collective: throw InputError if it links a component of the
       * vertex @p other prescribes (prescribed_point_dof()).
       */
      virtual void
      check_prescribed_vertex(const Problem<dim> &problem, const Interface<dim> &other) const;

      /**
       * @brief Collective: add the displacements it prescribes at time @p t to
       * @p values, and throw InputError if they are not finite.
       */
      virtual void
      add_prescribed_values(const Problem<dim>                        &problem,
                            double                                     t,
                            std::map<types::global_dof_index, double> &values) const;

      /**
       * @brief Collective: the largest change over a load step of what it
       * prescribes at this rank's vertices (a norm over the components).
       */
      virtual double
      largest_increment(const Problem<dim> &problem, const LoadSteps &steps) const;

      /** @brief Collective: warn on @p out if what it prescribes is not zero at t = 0. */
      virtual void
      warn_if_not_ramped(const Problem<dim> &problem, const ConditionalOStream &out) const;

      /**
       * @brief Collective: warn on @p out if what it applies is taken by a
       * support instead of the body: @p constraints are the Newton system's
       * (a DoF a Dirichlet condition holds is constrained to a value, with
       * no entries); @p end_time bounds the load path.
       */
      virtual void
      warn_if_held(const Problem<dim>              &problem,
                   const AffineConstraints<double> &constraints,
                   double                           end_time,
                   const ConditionalOStream        &out) const;

      /**
       * @brief The DoFs of component @p c of its boundary that it prescribes;
       * none if it prescribes no boundary's (the linked DoFs' checks).
       */
      virtual std::optional<IndexSet>
      prescribed_boundary_dofs(const Problem<dim> &problem, unsigned int c) const;

      /** @brief The DoF of component @p c of the vertex it prescribes, if any. */
      virtual std::optional<types::global_dof_index>
      prescribed_point_dof(unsigned int c) const;

      /** @brief Whether it has a face term on the boundary @p id. */
      virtual bool
      acts_on_faces_of(types::boundary_id id) const;

      /** @brief Its face term in the residual and the Jacobian. */
      virtual void
      assemble_face(const Problem<dim> &problem, const FaceSystem<dim> &face) const;

      /**
       * @brief Collective: throw InputError if its data were not finite
       * where evaluated since the last call.
       */
      virtual void
      check_finite(MPI_Comm communicator) const;

      /**
       * @brief Its global terms (forces on DoFs, not on faces), through @p
       * constraints into @p system_rhs, and the forces into @p external_force.
       */
      virtual void
      assemble_global(const Problem<dim>              &problem,
                      const AffineConstraints<double> &constraints,
                      TrilinosWrappers::MPI::Vector   &system_rhs,
                      TrilinosWrappers::MPI::Vector   &external_force) const;

      /** @brief Add the boundaries whose reactions it takes to @p ids (each once). */
      virtual void
      add_supported_boundaries(std::vector<types::boundary_id> &ids) const;

      /**
       * @brief Add its part of the reactions on the boundaries @p ids (those
       * of add_supported_boundaries()) to @p reactions, each DoF once
       * (@p claimed: those counted already).
       */
      virtual void
      add_reactions(const Problem<dim>                    &problem,
                    const ReactionInputs<dim>             &inputs,
                    const std::vector<types::boundary_id> &ids,
                    std::vector<Tensor<1, dim>>           &reactions,
                    IndexSet                              &claimed) const;

      /** @brief Add its columns of the statistics (besides the supported boundaries'). */
      virtual void
      add_statistics_columns(StatisticsWriter::Supports &supports) const;

      /** @brief Add its values of those columns to @p stats (collective). */
      virtual void
      add_statistics(const Problem<dim>        &problem,
                     const ReactionInputs<dim> &inputs,
                     StepStatistics            &stats) const;

      /** @brief Add where it holds the body to @p supports (the rigid-motion check). */
      virtual void
      add_supports(std::vector<Support<dim>> &supports) const;

      /**
       * @brief Error estimate: clear in @p free the components it prescribes
       * on the boundary @p id (they take any traction).
       */
      virtual void
      hold_components(types::boundary_id id, std::vector<bool> &free) const;

      /**
       * @brief Error estimate: add the traction it prescribes at @p x on the
       * boundary @p id, where the displacement is @p u, to @p load.
       */
      virtual void
      add_boundary_load(const Problem<dim>   &problem,
                        types::boundary_id    id,
                        const Point<dim>     &x,
                        const Tensor<1, dim> &u,
                        Vector<double>       &load) const;

    private:
      const std::string path;
    };

    /**
     * @brief A condition on one boundary of the mesh, given by its id or its
     * name in `Boundary id`.
     */
    template <int dim> class OnBoundary : public Interface<dim>
    {
    public:
      /**
       * @brief What a condition on a boundary does there: a load has face
       * terms (acts_on_faces_of()), a support takes the boundary's reaction
       * (add_supported_boundaries()), an elastic support both; a linked
       * boundary neither (it acts through its constraints, add_linked_constraints()).
       */
      enum class Role
      {
        load,
        support,
        elastic_support,
        linked
      };

      /** Reads `Boundary id` of the current subsection. */
      OnBoundary(const ParameterHandler &prm, const std::string &section, Role role);

      /** @brief False where `Boundary id = -1`. */
      bool
      used() const override;

      void
      resolve_boundaries(const BoundaryResolver &resolve) override;

      std::vector<types::boundary_id>
      boundaries() const override;

      bool
      acts_on_faces_of(types::boundary_id id) const override;

      /** @brief Its boundary, for a support. */
      void
      add_supported_boundaries(std::vector<types::boundary_id> &ids) const override;

      /** @brief Declare `Boundary id`, documented with @p what. */
      static void
      declare_boundary(ParameterHandler &prm, const std::string &what);

    protected:
      types::boundary_id boundary_id = 0;

    private:
      std::string boundary_name; ///< a mesh's boundary name, resolved to boundary_id by the run
      bool        is_used = false;
      const Role  role;
    };

    /**
     * @brief The vertex a point entry (@p entry) of the current subsection
     * names; none when it is empty. Errors name @p section and describe the
     * point as @p what.
     */
    template <int dim>
    std::optional<Point<dim>>
    parse_point(const ParameterHandler &prm,
                const std::string      &section,
                const std::string      &entry = "Point",
                const std::string      &what  = "a vertex of the mesh");

    /**
     * @brief The value at time @p t of @p function, a function of t only (a
     * resultant force), taken at the origin.
     */
    template <int dim>
    Vector<double>
    value_at_time(Parameters::BoundaryFunction<dim> &function, const double t)
    {
      Vector<double> value(dim);
      function.set_time(t);
      function.vector_value(Point<dim>(), value);
      return value;
    }

    /** @brief The registry of the boundary condition kinds, by the word(s) before the name. */
    template <int dim> using Registry = PluginRegistry<Interface<dim>>;

    /** @brief The registered kinds: `Neumann`, `Spring`, ... */
    std::vector<std::string>
    kinds();

    /**
     * @brief Declare the condition subsections @p sections names (those not
     * yet declared) in `Boundary conditions`.
     */
    template <int dim>
    void
    declare_parameters(ParameterHandler &prm, const Parameters::ConditionSections &sections);

    /**
     * @brief The conditions of the subsections @p sections names, in the
     * order of the registry's kinds, then of @p sections, those at one vertex
     * last (Interface::at_one_vertex()); the unused ones left out.
     */
    template <int dim>
    std::vector<std::unique_ptr<Interface<dim>>>
    create(ParameterHandler &prm, const Parameters::ConditionSections &sections);

    /**
     * @brief Register the kind @p Kind<dim> in Registry<dim>: an unused
     * condition is built as nothing.
     */
    template <int dim, template <int> class Kind>
    void
    register_kind_for(const std::string &name, const std::string &description)
    {
      Registry<dim>::add(
          name,
          description,
          &Kind<dim>::declare_parameters,
          [](ParameterHandler &prm, const std::string &section) -> std::unique_ptr<Interface<dim>> {
            std::unique_ptr<Interface<dim>> condition = std::make_unique<Kind<dim>>(prm, section);
            return condition->used() ? std::move(condition) : nullptr;
          });
    }

    /** @brief register_kind_for() for dim = 2 and 3 (SL_REGISTER_BOUNDARY_CONDITION). */
    template <template <int> class Kind>
    bool
    register_kind(const std::string &name, const std::string &description)
    {
      register_kind_for<2, Kind>(name, description);
      register_kind_for<3, Kind>(name, description);
      return true;
    }
  } // namespace BoundaryConditions
} // namespace StabilizedLagrangian

/**
 * @brief Register a boundary condition kind, at namespace scope of its `.cc`
 * file: `SL_REGISTER_BOUNDARY_CONDITION(Neumann, "Neumann", "prescribed traction")`
 * makes each subsection `Boundary conditions/Neumann <name>` a `Neumann<dim>`,
 * built by the constructor `Neumann<dim>(ParameterHandler &prm, const
 * std::string &section)` from the subsection and its path, its entries
 * declared by `static void Neumann<dim>::declare_parameters(ParameterHandler &)`.
 */
#define SL_REGISTER_BOUNDARY_CONDITION(kind, name, description)                                \
  [[maybe_unused]] static const bool SL_PLUGIN_CONCATENATE(sl_boundary_condition_, __LINE__) = \
      ::StabilizedLagrangian::BoundaryConditions::register_kind<kind>(name, description)
