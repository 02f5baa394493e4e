#include <deal.II/base/utilities.h>

#include <stabilized_lagrangian/contact/friction_zones.h>
#include <stabilized_lagrangian/parameters.h>

#include <algorithm>

namespace StabilizedLagrangian
{
  namespace Contact
  {
    FrictionZones::FrictionZones(ParameterHandler &prm, const std::vector<std::string> &zone_names)
    {
      prm.enter_subsection("Contact");
      default_friction_law = FrictionLaws::create(prm, "Contact");
      prm.leave_subsection();
      for (const auto &name : zone_names)
        {
          prm.enter_subsection("Contact");
          prm.enter_subsection("Zone " + name);
          const auto boundaries = Utilities::split_string_list(prm.get("Boundary ids"));
          if (!boundaries.empty())
            zones.push_back(
                Zone{name, boundaries, FrictionLaws::create(prm, "Contact/Zone " + name)});
          prm.leave_subsection();
          prm.leave_subsection();
        }
    }

    bool
    FrictionZones::any_law(
        const std::function<bool(const FrictionLaws::Interface &)> &property) const
    {
      return property(*default_friction_law) ||
             std::any_of(zones.begin(), zones.end(), [&](const auto &zone) {
               return property(*zone.friction_law);
             });
    }

    bool
    FrictionZones::any_friction() const
    {
      return any_law([](const auto &law) { return law.has_friction(); });
    }

    bool
    FrictionZones::any_pressure_dependent_threshold() const
    {
      return any_law([](const auto &law) { return law.threshold_depends_on_pressure(); });
    }

    void
    FrictionZones::resolve(
        const std::function<types::boundary_id(const std::string &, const std::string &)> &resolve,
        const std::set<types::boundary_id> &contact_boundaries)
    {
      zone_of_boundary.clear();
      for (unsigned int z = 0; z < zones.size(); ++z)
        for (const auto &entry : zones[z].boundaries)
          {
            const std::string        where    = "Contact/Zone " + zones[z].name + "/Boundary ids";
            const auto               id       = Parameters::boundary_id_or_name(entry, where);
            const types::boundary_id boundary = id ? *id : resolve(entry, where);
            if (contact_boundaries.count(boundary) == 0)
              throw InputError(where + ": boundary " + entry +
                               " is not a contact boundary (Contact/Contact boundary ids).");
            if (!zone_of_boundary.emplace(boundary, z + 1).second)
              throw InputError(where + ": boundary " + entry + " is already in another zone.");
          }
    }
  } // namespace Contact
} // namespace StabilizedLagrangian
