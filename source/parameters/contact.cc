#include <stabilized_lagrangian/contact/friction_law.h>
#include <stabilized_lagrangian/parameters.h>
#include <stabilized_lagrangian/plugins.h>

#include <string>
#include <vector>

/** @file The `Contact` section and its zones (Parameters::Contact). */

namespace StabilizedLagrangian
{
  namespace Parameters
  {
    std::optional<types::boundary_id>
    boundary_id_or_name(const std::string &entry, const std::string &name)
    {
      if (entry.empty())
        throw InputError(name + ": an empty boundary.");
      if (entry.find_first_not_of("0123456789") != std::string::npos)
        return std::nullopt;
      const auto id = decimal_integer(entry, numbers::internal_face_boundary_id - 1);
      if (!id)
        throw InputError(name + " = " + entry + ": a boundary id is an integer from 0 to " +
                         std::to_string(numbers::internal_face_boundary_id - 1) +
                         ", or the name of a boundary of the mesh.");
      return static_cast<types::boundary_id>(*id);
    }

    namespace
    {
      /** The entries of `Contact` that name its surfaces and the augmentation parameters. */
      void
      declare_surface_entries(ParameterHandler &prm)
      {
        prm.declare_entry("Contact boundary ids",
                          "2",
                          Patterns::List(Patterns::Anything(), 1),
                          "Boundaries of the slave contact surface Γc, which carries the "
                          "multipliers: boundary ids, or names of the mesh's boundaries (the "
                          "physical groups of a Gmsh mesh).");
        prm.declare_entry("Master boundary ids",
                          "",
                          Patterns::List(Patterns::Anything(), 0),
                          "Boundaries of the master surface of a second deformable body (ids or "
                          "names): each slave point is paired with the closest point of the "
                          "deformed master surface. Empty: the master is the rigid `Obstacle`.");
        prm.declare_entry(
            "Master surface search",
            "distributed",
            Patterns::Selection("distributed|replicated"),
            "How the ranks find the master faces of their slave points (doc/formulation.md, "
            "\"Distributed contact search\"). distributed: a rank holds only the master faces "
            "that come within the search distance of its own slave faces, gathered from their "
            "owners as the bodies move (memory per rank: its share and the faces near it). "
            "replicated: every rank holds the whole master surface (memory per rank grows with "
            "the surface; for comparison). Both give the same pairings within the search "
            "distance.");
        prm.declare_entry("Search distance",
                          "0",
                          Patterns::Double(0.),
                          "With Master surface search = distributed: the distance (mm) from a "
                          "rank's deformed slave faces within which it holds every master face; "
                          "slave points further than that from the master surface are paired with "
                          "the nearest face held, or open. 0: twice the largest diameter of the "
                          "contact faces (slave and master).");
        prm.declare_entry("r_n",
                          "1e4",
                          Patterns::Anything(),
                          "Normal augmentation parameter r_n > 0 (N/mm^3), or `automatic`: "
                          "r_n = C_n E / h from the Young's modulus E of the material and the "
                          "largest face diameter h on Γc (doc/robustness.md gives C_n).");
        prm.declare_entry("r_t",
                          "1",
                          Patterns::Anything(),
                          "Tangential augmentation parameter r_t > 0 (1/mm), or `automatic`: "
                          "r_t = C_t / l with l the largest displacement increment the Dirichlet "
                          "data prescribe over one load step (h without prescribed motion): "
                          "r_t l, not μ/h, sets the good range (doc/robustness.md gives C_t).");
        prm.declare_entry("Automatic r_n factor",
                          "1",
                          Patterns::Double(),
                          "With r_n = automatic: a factor > 0 on the automatic value (to scan "
                          "around it).");
        prm.declare_entry("Automatic r_t factor",
                          "1",
                          Patterns::Double(),
                          "With r_t = automatic: a factor > 0 on the automatic value.");
      }

      /** The entries of `Contact` that choose its discretisation and conditions. */
      void
      declare_discretisation_entries(ParameterHandler  &prm,
                                     const std::string &fe_pairs,
                                     const std::string &fe_pair_documentation)
      {
        prm.declare_entry(
            "Finite element pair", "Q1/P1", Patterns::Selection(fe_pairs), fe_pair_documentation);
        prm.declare_entry(
            "Contact quadrature",
            "Gauss-Lobatto",
            Patterns::Selection("Gauss|Gauss-Lobatto"),
            "Quadrature on Γc; the contact and stick/slip statuses live at its "
            "points. Gauss-Lobatto (degree max(k, m) + 1 points per direction) puts them "
            "at the multiplier nodes when m >= k.");
        prm.declare_entry(
            "Complementarity",
            "automatic",
            Patterns::Selection("automatic|pointwise|weighted"),
            "Where the contact and friction conditions hold. pointwise: at every contact "
            "integration point, on lambda_n - r_n g_n (the seed's formulation; its discrete "
            "solution depends on r_n where the multiplier nodes are not the integration points, "
            "e.g. on non-matching meshes: on prm/patin_deformable_block.prm r_n factor 100 moves "
            "the nodal pressures by 1.8 x the peak against factor 1). weighted: once per "
            "multiplier node j on the weighted gap and slip, g_j = int psi_j g_n / int psi_j and "
            "likewise the slip increment (mortar conditions): lambda_j >= 0, g_j >= 0, lambda_j "
            "g_j = 0 and Coulomb's law per node, whose discrete solution does not depend on r_n or "
            "r_t (the same sweep: 1e-13 of the peak); the displacement sees the multiplier field "
            "itself. Needs every multiplier node of the contact surface free (no hanging node on "
            "it, no multiplier on a coarser mesh) and no contact zones. automatic: weighted for "
            "two deformable bodies and for dual pairs, pointwise against a rigid obstacle (the "
            "seed's formulation, which its results are compared with) and wherever weighted "
            "does not apply (contact zones, constrained multiplier nodes, local refinement of a 3D "
            "contact surface); the log and run_summary.csv (weighted_complementarity) give the "
            "choice (doc/formulation.md, \"Which conditions by default\").");
        prm.declare_entry("Check inf-sup",
                          "false",
                          Patterns::Bool(),
                          "Compute the discrete inf-sup constant beta_h of the pair on the run's "
                          "mesh before each refinement cycle's load path (as `--inf-sup`, one MPI "
                          "rank: skipped with a note on more), write it to refinement_cycles.csv "
                          "and run_summary.csv (inf_sup_beta), and warn when it is zero or falls "
                          "under refinement (below 0.8 of its largest earlier value): the pair is "
                          "then not inf-sup stable and the multipliers oscillate. One solve per "
                          "normal multiplier and a dense eigenproblem of their number: for "
                          "checking a pair, not for every production run.");
      }
    } // namespace

    void
    Contact::declare_parameters(ParameterHandler  &prm,
                                const std::string &fe_pairs,
                                const std::string &fe_pair_documentation)
    {
      prm.enter_subsection("Contact");
      declare_surface_entries(prm);
      declare_discretisation_entries(prm, fe_pairs, fe_pair_documentation);
      FrictionLaws::declare_parameters(prm);
      prm.leave_subsection();
    }

    void
    Contact::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Contact");
      const auto parse_boundaries = [&prm](const std::string            &entry,
                                           std::set<types::boundary_id> &ids,
                                           std::vector<std::string>     &names) {
        ids.clear();
        names.clear();
        for (const auto &item : Utilities::split_string_list(prm.get(entry)))
          {
            const auto id = boundary_id_or_name(item, "Contact/" + entry);
            if (id)
              ids.insert(*id);
            else
              names.push_back(item);
          }
      };
      parse_boundaries("Contact boundary ids", boundary_ids, boundary_names);
      parse_boundaries("Master boundary ids", master_ids, master_names);
      replicated_search = prm.get("Master surface search") == "replicated";
      search_distance   = prm.get_double("Search distance");
      // a positive number, or `automatic` (times a positive factor)
      const auto parse_parameter = [&prm](const std::string &name,
                                          const std::string &unit,
                                          double            &value,
                                          bool              &automatic,
                                          double            &factor) {
        const std::string text = Utilities::trim(prm.get(name));
        automatic              = text == "automatic";
        factor                 = prm.get_double("Automatic " + name + " factor");
        if (!(factor > 0.) || !std::isfinite(factor))
          throw InputError("Contact/Automatic " + name + " factor must be > 0, got " +
                           prm.get("Automatic " + name + " factor") + ".");
        if (automatic)
          return;
        std::size_t end = 0;
        try
          {
            value = std::stod(text, &end);
          }
        catch (const std::exception &)
          {
            end = 0;
          }
        if (end == 0 || end != text.size() || !(value > 0.) || !std::isfinite(value))
          throw InputError("Contact/" + name + " must be a number > 0 (" + unit +
                           ") or `automatic`, got '" + text + "'.");
      };
      parse_parameter("r_n", "N/mm^3", r_n, r_n_automatic, r_n_factor);
      parse_parameter("r_t", "1/mm", r_t, r_t_automatic, r_t_factor);
      fe_pair       = prm.get("Finite element pair");
      check_inf_sup = prm.get_bool("Check inf-sup");
      quadrature    = prm.get("Contact quadrature") == "Gauss" ? ContactQuadrature::gauss
                                                               : ContactQuadrature::gauss_lobatto;
      complementarity_automatic = prm.get("Complementarity") == "automatic";
      // with `automatic`, pointwise until the run chooses (ContactBoundary::choose_complementarity)
      complementarity = prm.get("Complementarity") == "weighted" ? Complementarity::weighted
                                                                 : Complementarity::pointwise;
      prm.leave_subsection();
    }

    void
    declare_contact_zones(ParameterHandler &prm, const std::vector<std::string> &names)
    {
      prm.enter_subsection("Contact");
      for (const auto &name : names)
        if (!prm.subsection_path_exists({"Zone " + name}))
          {
            prm.enter_subsection("Zone " + name);
            prm.declare_entry("Boundary ids",
                              "",
                              Patterns::Anything(),
                              "Contact boundaries (ids or names, some of `Contact boundary ids`) "
                              "whose friction law is this zone's `Friction law` instead of "
                              "Contact/Friction law; empty: the zone is unused.");
            FrictionLaws::declare_parameters(prm);
            prm.leave_subsection();
          }
      prm.leave_subsection();
    }
  } // namespace Parameters
} // namespace StabilizedLagrangian
