#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/quadrature.h>

#include <stabilized_lagrangian/contact/contact_surface.h>
#include <stabilized_lagrangian/contact/friction_law.h>

#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

namespace StabilizedLagrangian
{
  namespace Contact
  {
    using namespace dealii;

    /**
     * @brief The friction laws of Γc: `Contact/Friction law`, the default, and
     * the contact zones (`Contact/Zone <name>`), each a set of contact
     * boundaries with its own law (doc/formulation.md, seed eq. (8): the
     * threshold s(λ_n) of a point is its zone's).
     *
     * A contact point's zone is a number: 0 the default law, z the z-th zone
     * (1-based). Iterating over the object lists the zones.
     */
    class FrictionZones
    {
    public:
      /** @brief One zone: its name, its boundaries as given, its law. */
      struct Zone
      {
        std::string                              name;
        std::vector<std::string>                 boundaries; ///< ids or names, as given
        std::unique_ptr<FrictionLaws::Interface> friction_law;
      };

      /** @brief No law yet (the problem reads them in its order of the input). */
      FrictionZones() = default;

      /**
       * @brief Read the default law and the zones named in @p zone_names from
       * the `Contact` subsection of @p prm; a zone without boundaries is left out.
       */
      FrictionZones(ParameterHandler &prm, const std::vector<std::string> &zone_names);

      /** @brief The law of zone @p zone (0: the default). */
      const FrictionLaws::Interface &
      law_of(const unsigned int zone) const
      {
        return zone == 0 ? *default_friction_law : *zones[zone - 1].friction_law;
      }

      /** @brief The default law (the weighted conditions have no zones). */
      const std::unique_ptr<FrictionLaws::Interface> &
      default_law() const
      {
        return default_friction_law;
      }

      /** @brief Whether the default law or some zone's has friction (then Λ exists on Γc). */
      bool
      any_friction() const;

      /** @brief Whether some law's threshold depends on the pressure (the friction loop). */
      bool
      any_pressure_dependent_threshold() const;

      /**
       * @brief Resolve the zones' boundaries to the mesh's ids (@p resolve for
       * a name), each a contact boundary in @p contact_boundaries and in one
       * zone only; throws an InputError otherwise.
       */
      void
      resolve(const std::function<types::boundary_id(const std::string &, const std::string &)>
                                                 &resolve,
              const std::set<types::boundary_id> &contact_boundaries);

      /** @brief The zone of the contact boundary @p id (0: in none). */
      unsigned int
      zone_of(const types::boundary_id id) const
      {
        const auto found = zone_of_boundary.find(id);
        return found == zone_of_boundary.end() ? 0 : found->second;
      }

      /** @brief Each contact point's zone, from its face's boundary. */
      template <int dim>
      void
      assign(const std::vector<ContactFace<dim>> &faces,
             const Quadrature<dim - 1>           &contact_quadrature,
             std::vector<ContactPointState<dim>> &states) const
      {
        for (const auto &face : faces)
          {
            const unsigned int zone = zone_of(face.cell->face(face.face_no)->boundary_id());
            const unsigned int n_points =
                face.segments ? face.segments->size() : contact_quadrature.size();
            for (unsigned int q = 0; q < n_points; ++q)
              states[face.first_point + q].zone = zone;
          }
      }

      /** @brief The number of zones. */
      std::size_t
      size() const
      {
        return zones.size();
      }

      /** @brief Whether there are no zones (the default law everywhere). */
      bool
      empty() const
      {
        return zones.empty();
      }

      /** @brief The zones, in the order of the input. */
      typename std::vector<Zone>::const_iterator
      begin() const
      {
        return zones.begin();
      }
      typename std::vector<Zone>::const_iterator
      end() const
      {
        return zones.end();
      }

    private:
      /** Whether the default law or some zone's has @p property. */
      bool
      any_law(const std::function<bool(const FrictionLaws::Interface &)> &property) const;

      /** `Contact/Friction law` */
      std::unique_ptr<FrictionLaws::Interface> default_friction_law;
      std::vector<Zone>                        zones;
      /** the zone (1-based) of each contact boundary in a zone */
      std::map<types::boundary_id, unsigned int> zone_of_boundary;
    };
  } // namespace Contact
} // namespace StabilizedLagrangian
