#pragma once

#include <deal.II/base/function_parser.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/parsed_function.h>
#include <deal.II/base/tensor.h>

#include <deal.II/fe/component_mask.h>

#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace StabilizedLagrangian
{
  /**
   * Typed parameter structs, each declared and parsed once and passed down.
   * The plug-in areas (geometry, obstacle, material, friction law) declare
   * their own subsections.
   */
  namespace Parameters
  {
    using namespace dealii;

    /**
     * @brief Contact quadrature: statuses live at these points
     * (doc/formulation.md, "Unknowns and spaces").
     */
    enum class ContactQuadrature
    {
      gauss,
      gauss_lobatto
    };

    /**
     * @brief Where the contact and friction conditions hold
     * (doc/formulation.md, "Weighted complementarity").
     */
    enum class Complementarity
    {
      pointwise, ///< at each contact integration point (the seed's formulation)
      weighted   ///< per multiplier node on the weighted gap ∫ψ_j g_n (mortar)
    };

    /**
     * @brief A boundary given in the prm: its id if @p entry is a number,
     * nothing if it is a name (resolved once the mesh is known); InputError
     * naming the entry @p name if the id is out of range.
     */
    std::optional<types::boundary_id>
    boundary_id_or_name(const std::string &entry, const std::string &name);

    /** @brief `Contact` subsection: Γc, augmentation parameters, FE pair. */
    struct Contact
    {
      std::set<types::boundary_id> boundary_ids;
      std::vector<std::string>     boundary_names; ///< mesh boundary names, resolved by the run
      /** master surface of a second deformable body; empty: the rigid obstacle */
      std::set<types::boundary_id> master_ids;
      std::vector<std::string>     master_names; ///< resolved by the run
      /** every rank holds the whole master surface (`Master surface search = replicated`) */
      bool replicated_search = false;
      /** `Search distance` (mm); 0: automatic */
      double      search_distance = 0.;
      double      r_n             = 0.; ///< as given; 0 with `automatic` (ChosenParameters::r_n)
      double      r_t             = 0.;
      bool        r_n_automatic   = false;
      bool        r_t_automatic   = false;
      double      r_n_factor      = 1.; ///< multiplies the automatic r_n
      double      r_t_factor      = 1.;
      std::string fe_pair;
      bool        check_inf_sup = false; ///< β_h of the pair before each cycle (`Check inf-sup`)
      ContactQuadrature quadrature = ContactQuadrature::gauss_lobatto;
      /** as given; pointwise with `automatic` (ChosenParameters::complementarity) */
      Complementarity complementarity = Complementarity::pointwise;
      /** `Complementarity = automatic`: weighted for two bodies
       * (ContactBoundary::choose_complementarity) */
      bool complementarity_automatic = false;

      static void
      declare_parameters(ParameterHandler  &prm,
                         const std::string &fe_pairs,
                         const std::string &fe_pair_documentation);
      void
      parse_parameters(ParameterHandler &prm);
    };

    /**
     * @brief A function of the `Boundary conditions` that notes the first
     * non-finite value it returns (0/0, the square root of a negative number,
     * a NaN constant), with its entry, time and point, so that the run stops
     * with that message instead of carrying NaN into the solution and output.
     */
    template <int dim> class BoundaryFunction : public Functions::ParsedFunction<dim>
    {
    public:
      /** @param entry the subsection path named in the message, e.g. `Boundary conditions/Dirichlet
       * 1/Displacement` */
      explicit BoundaryFunction(const std::string &entry, unsigned int n_components = dim);

      void
      vector_value(const Point<dim> &point, Vector<double> &values) const override;
      double
      value(const Point<dim> &point, const unsigned int component = 0) const override;

      /**
       * Collective: if this function returned a non-finite value on any rank
       * since the last call, throw InputError naming the entry, the time and the
       * point on every rank.
       */
      void
      check_finite(const MPI_Comm communicator) const;

      /** The subsection path of the function, for messages. */
      const std::string &
      name() const
      {
        return entry;
      }

    private:
      void
      note(const Point<dim> &point, const double value, const unsigned int component) const;

      const std::string   entry;
      mutable std::string failure;
    };

    /**
     * @brief The vector function (@p n_components components of the
     * coordinates and t, dim by default) in subsection @p name of the current
     * subsection, checked: its variable names, its constants, and that it
     * parses; errors name @p parent/@p name.
     */
    template <int dim>
    std::shared_ptr<BoundaryFunction<dim>>
    parse_function(ParameterHandler  &prm,
                   const std::string &parent,
                   const std::string &name,
                   unsigned int       n_components = dim);

    /**
     * @brief Declare in the current subsection the entries of a function
     * (@p n_components components of the coordinates and t, dim by default;
     * values in @p unit), which parse_function() reads.
     */
    template <int dim>
    void
    declare_function(ParameterHandler  &prm,
                     const std::string &unit,
                     unsigned int       n_components = dim);

    /**
     * @brief The condition subsections of `Boundary conditions` a parameter
     * text holds: `Dirichlet <name>`, `Neumann <name>`, `Spring <name>`,
     * `Rigid plate <name>`, any number of each (the names are the words after
     * the kind).
     */
    struct ConditionSections
    {
      /** per kind (`Dirichlet`, `Neumann`, ...), the names of its subsections */
      std::map<std::string, std::vector<std::string>> conditions;
      /** the contact zones: `Contact/Zone <name>` */
      std::vector<std::string> zones;
    };

    /**
     * @brief Declare `Contact/Zone <name>` for each of @p names (those not yet
     * declared): the zone's contact boundaries and its own `Friction law`.
     */
    void
    declare_contact_zones(ParameterHandler &prm, const std::vector<std::string> &names);

    /**
     * @brief The condition subsections of @p text (a parameter file with its
     * includes expanded), read before it is parsed to declare them; throws
     * InputError for a `Boundary conditions` subsection of no known kind.
     */
    ConditionSections
    condition_sections(const std::string &text);

    /** @brief `Load stepping` subsection. */
    struct LoadStepping
    {
      double       end_time;
      unsigned int n_steps;
      unsigned int max_cuts;
      double       wall_time_limit = 0.; ///< s; 0: none

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    /**
     * @brief What the Newton tolerance is compared with (doc/formulation.md,
     * "Newton stopping criterion").
     */
    enum class ResidualCriterion
    {
      scaled,   ///< each block against its own scale: forces, gaps, slips (default)
      absolute, ///< the seed's: the residual in N (multiplier rows times r_n, r_t)
      relative  ///< that residual against the first one of the Newton loop
    };

    /**
     * @brief How an outer loop's nonlinearity is solved: by its fixed point
     * (frozen in the inner loops), or folded into the generalized Newton.
     */
    enum class LoopMethod
    {
      fixed_point,
      newton
    };

    /**
     * @brief `Nonlinear solver` subsection: limits and tolerances of the nested loops
     * (doc/formulation.md, "Nested loops").
     */
    struct NonlinearSolver
    {
      LoopMethod   geometry_method;
      LoopMethod   friction_method;
      LoopMethod   status_method;
      unsigned int max_newton_per_step; ///< budget of Newton iterations per load step
      unsigned int geometry_max_iterations;
      double       geometry_tolerance;
      unsigned int friction_max_iterations;
      double       friction_tolerance;
      unsigned int status_max_iterations;
      unsigned int newton_max_iterations;
      unsigned int line_search_steps; ///< halvings of the Newton step, 0: none
      /** `Predictor = extrapolation`: a step starts from the last one's change, scaled */
      bool              extrapolate = false;
      double            newton_tolerance;
      ResidualCriterion newton_criterion;
      /** `Stopping = adaptive`: Newton also stops at a fraction of the estimated error */
      bool   adaptive_stopping = false;
      double adaptive_fraction = 0.02;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    /** @brief `Linear solver` subsection. */
    struct LinearSolver
    {
      /** one factorisation per Newton system, or GMRES with a block preconditioner */
      bool iterative = false;
      /** `Method = automatic`: iterative in 3D from automatic_threshold unknowns on */
      bool                    automatic           = false;
      types::global_dof_index automatic_threshold = 20000;
      std::string             direct_solver;
      double                  maximum_forcing_term = 1e-3; ///< the largest relative GMRES tolerance
      double schur_augmentation = 10.; ///< c of the augmented preconditioner (Γ = c diag(X̂)⁻¹)
      bool   rigid_body_modes =
          false; ///< the AMG's near-null space: rotations too, not only translations
      unsigned int maximum_iterations = 300; ///< GMRES iterations per Newton system
      /** GMRES tolerance from Eisenstat–Walker, or from the Newton tolerance (default) */
      bool         eisenstat_walker     = false;
      bool         null_pivot_detection = false; ///< MUMPS: solve singular systems
      unsigned int threads_per_rank     = 1;     ///< BLAS/OpenMP threads of each MPI rank
      int          workspace_increase   = 20;    ///< MUMPS ICNTL(14), percent

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    /**
     * @brief `Adaptive refinement` subsection: refinement around the active
     * set, solving the whole load path again on each new mesh.
     */
    struct AdaptiveRefinement
    {
      enum class Criterion
      {
        active_set, ///< refine a band around the points in contact
        kelly,      ///< refine the cells with the largest Kelly error indicators
        estimator,  ///< refine the cells with the largest residual error indicators η_K
        uniform     ///< refine every cell
      };
      unsigned int cycles    = 0; ///< solves on refined meshes after the first one
      Criterion    criterion = Criterion::active_set;
      double       band      = 0.5; ///< width of the refined band, in active-zone sizes
      double       fraction  = 0.3; ///< Kelly, estimator: fraction of the cells refined
      /** Kelly, estimator: `fraction` is that of the squared indicators' sum (Dörfler) */
      bool bulk_marking = false;
      /** measure each cycle's displacement against the last cycle's (cycle_errors.csv) */
      bool errors_against_last_cycle = false;
      /** stop the cycles once the estimated relative energy error is at most this (0: off) */
      double target_error = 0.;
      /** ... and the estimated relative L2 error of the contact pressure (0: off) */
      double target_pressure_error = 0.;

      /** @brief Whether the cycles stop at a target rather than run them all. */
      bool
      targeted() const
      {
        return target_error > 0. || target_pressure_error > 0.;
      }

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    /** @brief `Output` subsection. */
    struct Output
    {
      std::string  directory;
      bool         write_vtu;
      bool         write_profiles;
      bool         log_newton;              ///< print every Newton iterate and line-search trial
      unsigned int checkpoint_interval = 0; ///< load steps between checkpoints, 0: none

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    /**
     * @brief Declare every entry of a run in dimension @p dim, plug-in
     * subsections included, with one condition of each kind (`Dirichlet 1`,
     * `Neumann 1`, `Spring 1`) as the boundary conditions' template.
     */
    template <int dim>
    void
    declare_all(ParameterHandler &prm);

    /**
     * @brief Read `Dimension` from a parameter file or string without declaring the rest.
     * @param text file name, or the file content if @p is_file is false
     */
    unsigned int
    read_dimension(const std::string &text, const bool is_file);

    /**
     * @brief Parse a parameter file (or string) into @p prm, declared by
     * declare_all<dim>, with a clear error on failure; the boundary condition
     * subsections the text names are declared first.
     * @return the condition subsections @p prm holds: those the text names and
     * declare_all's template, each kind in ParameterHandler's order of subsections
     */
    template <int dim>
    ConditionSections
    parse(ParameterHandler &prm, const std::string &text, const bool is_file);

    /**
     * @brief @p message with the file and line (`'file' line N: `) of the
     * entry or subsection of the parameter file parsed last that it begins
     * with (`Load stepping/End time must be > 0, ...`), as is when it names none.
     */
    std::string
    located(const std::string &message);

    /**
     * @brief The value of @p text if it is a decimal integer (digits only, no
     * sign) of at most @p max, else nothing: no overflow for any length.
     */
    std::optional<unsigned long long>
    decimal_integer(const std::string &text, const unsigned long long max);

    /**
     * @brief A file named in the parameters: as given if it exists (or is
     * absolute), else relative to the directory of the parameter file parsed last.
     */
    std::string
    input_path(const std::string &path);
  } // namespace Parameters
} // namespace StabilizedLagrangian
