#include <deal.II/base/utilities.h>

#include <stabilized_lagrangian/boundary_conditions/interface.h>
#include <stabilized_lagrangian/contact/friction_law.h>
#include <stabilized_lagrangian/discretization/fe_pair.h>
#include <stabilized_lagrangian/geometry/scene.h>
#include <stabilized_lagrangian/materials/material.h>
#include <stabilized_lagrangian/obstacles/obstacle.h>
#include <stabilized_lagrangian/parameters.h>
#include <stabilized_lagrangian/parameters/parameter_file.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <regex>
#include <map>
#include <sstream>

namespace StabilizedLagrangian
{
  namespace Parameters
  {
    namespace
    {
      /** The kinds of `Boundary conditions` subsections with their descriptions, for messages. */
      std::string
      condition_kinds_described()
      {
        std::string result;
        for (const auto &kind : StabilizedLagrangian::BoundaryConditions::kinds())
          result += (result.empty() ? "'" : ", '") + kind + " <name>' (" +
                    StabilizedLagrangian::BoundaryConditions::Registry<2>::description(kind) + ")";
        return result;
      }
    } // namespace

    namespace
    {
      /**
       * Call @p visit(line, statement) for each statement of the parameter
       * text @p text, with the number of the line it starts on, in
       * ParameterHandler's syntax: '#' starts a comment, a trailing backslash
       * continues a line.
       */
      template <typename Visit>
      void
      for_each_statement(const std::string &text, const Visit &visit)
      {
        std::istringstream lines(text);
        std::string        line, joined;
        bool               continued = false;
        unsigned int       start     = 1;
        for (unsigned int number = 1; std::getline(lines, line); ++number)
          {
            if (!continued)
              start = number;
            line = Utilities::trim(line.substr(0, line.find('#')));
            if (!line.empty() && line.back() == '\\')
              {
                joined += line.substr(0, line.size() - 1) + " ";
                continued = true;
                continue;
              }
            visit(start, Utilities::trim(joined + line));
            joined.clear();
            continued = false;
          }
      }

      /** The rest of @p statement after @p keyword and white space, or nothing. */
      std::optional<std::string>
      after_keyword(const std::string &statement, const std::string &keyword)
      {
        if (statement.rfind(keyword, 0) != 0 || statement.size() <= keyword.size() ||
            !std::isspace(static_cast<unsigned char>(statement[keyword.size()])))
          return std::nullopt;
        return Utilities::trim(statement.substr(keyword.size()));
      }
    } // namespace

    ConditionSections
    condition_sections(const std::string &text)
    {
      ConditionSections        sections;
      std::vector<std::string> path;
      for_each_statement(text, [&](unsigned int, const std::string &line) {
        if (line == "end")
          {
            if (!path.empty())
              path.pop_back();
            return;
          }
        const auto subsection = after_keyword(line, "subsection");
        if (!subsection)
          return;
        const std::string name = *subsection;
        if (path.size() == 1 && path[0] == "Boundary conditions")
          {
            std::vector<std::string> *list = nullptr;
            std::string               label;
            for (const auto &kind : StabilizedLagrangian::BoundaryConditions::kinds())
              if (name.rfind(kind + " ", 0) == 0)
                {
                  list  = &sections.conditions[kind];
                  label = Utilities::trim(name.substr(kind.size() + 1));
                }
            if (list == nullptr || label.empty())
              throw InputError(
                  "Boundary conditions/" + name + ": a boundary condition is a subsection " +
                  condition_kinds_described() + ", with any name, e.g. 'Dirichlet top'.");
            if (std::find(list->begin(), list->end(), label) == list->end())
              list->push_back(label);
          }
        if (path.size() == 1 && path[0] == "Contact" && name.rfind("Zone ", 0) == 0)
          {
            const std::string zone = Utilities::trim(name.substr(5));
            if (std::find(sections.zones.begin(), sections.zones.end(), zone) ==
                sections.zones.end())
              sections.zones.push_back(zone);
          }
        path.push_back(name);
      });
      return sections;
    }

    namespace
    {
      /** The condition subsections declare_all() declares as the template: `1` of each kind. */
      ConditionSections
      template_sections()
      {
        ConditionSections sections;
        for (const auto &kind : StabilizedLagrangian::BoundaryConditions::kinds())
          sections.conditions[kind] = {"1"};
        sections.zones = {"1"};
        return sections;
      }

      /**
       * The key ParameterHandler stores subsection @p name under: each
       * character outside [A-Za-z0-9] written as `_` and two hex digits. Its
       * subsections are in the order of their keys, the order in which the
       * conditions have always been applied and numbered.
       */
      std::string
      subsection_key(const std::string &name)
      {
        static const char *hex = "0123456789abcdef";
        std::string        key;
        for (const unsigned char c : name)
          if ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9'))
            key += static_cast<char>(c);
          else
            key += std::string{'_', hex[c / 16], hex[c % 16]};
        return key;
      }

      /** The names of @p names and @p more, each once, in ParameterHandler's order. */
      std::vector<std::string>
      merged(std::vector<std::string> names, const std::vector<std::string> &more)
      {
        for (const auto &name : more)
          if (std::find(names.begin(), names.end(), name) == names.end())
            names.push_back(name);
        std::sort(names.begin(), names.end(), [](const auto &a, const auto &b) {
          return subsection_key(a) < subsection_key(b);
        });
        return names;
      }

      /** The sections of @p text and the template's, each once, in ParameterHandler's order. */
      ConditionSections
      with_template(const ConditionSections &text)
      {
        ConditionSections result = template_sections();
        for (const auto &[kind, names] : text.conditions)
          result.conditions[kind] = merged(result.conditions[kind], names);
        result.zones = merged(result.zones, text.zones);
        return result;
      }
    } // namespace

    template <int dim>
    void
    declare_all(ParameterHandler &prm)
    {
      prm.declare_entry("Dimension",
                        "2",
                        Patterns::Integer(2, 3),
                        "2 (plane strain, or axisymmetric: Geometry/Axisymmetric) or 3.");
      Geometry::declare_parameters<dim>(prm);
      Obstacles::declare_parameters<dim>(prm);
      prm.enter_subsection("Obstacle");
      prm.enter_subsection("Motion");
      declare_function<dim>(prm,
                            "mm: the obstacle's translation d at time t; 0: fixed; only t is used");
      prm.declare_entry("Rotation centre",
                        dim == 2 ? "0, 0" : "0, 0, 0",
                        Patterns::List(Patterns::Double(), dim, dim),
                        "The point c the obstacle turns about (mm), where it is at rest; it moves "
                        "with the translation d.");
      prm.enter_subsection("Rotation");
      declare_function<dim>(prm,
                            dim == 2 ? "rad: the angle the obstacle has turned by about its "
                                       "rotation centre at time t, counter-clockwise; only t "
                                       "is used"
                                     : "rad: the rotation vector (axis times angle) the "
                                       "obstacle has turned by about its rotation centre at "
                                       "time t; only t is used",
                            dim == 2 ? 1 : 3);
      prm.leave_subsection();
      prm.leave_subsection();
      prm.leave_subsection();
      Materials::declare_parameters<dim>(prm);
      Contact::declare_parameters(prm,
                                  Discretization::Registry<dim>::pattern(),
                                  Discretization::Registry<dim>::documentation(
                                      "Displacement / multiplier spaces (λ_n and Λ together):"));
      StabilizedLagrangian::BoundaryConditions::declare_parameters<dim>(prm, template_sections());
      declare_contact_zones(prm, template_sections().zones);
      LoadStepping::declare_parameters(prm);
      NonlinearSolver::declare_parameters(prm);
      LinearSolver::declare_parameters(prm);
      AdaptiveRefinement::declare_parameters(prm);
      Output::declare_parameters(prm);
    }

    namespace
    {
      /**
       * ParameterHandler's message with "Line <N> of file <input string>"
       * replaced by the file and line the expanded line N came from (its
       * message for an unknown subsection lacks the closing '>').
       */
      std::string
      locate(const std::string &message, const ExpandedFile &file)
      {
        static const std::regex where("Line <([0-9]+)> of file <input string>?");
        std::smatch             match;
        if (!std::regex_search(message, match, where))
          return message;
        const unsigned long line = std::stoul(match[1]);
        if (line < 1 || line > file.origin.size())
          return message;
        const auto &[name, number] = file.origin[line - 1];
        return match.prefix().str() + "'" + name + "' line " + std::to_string(number) +
               match.suffix().str();
      }

      /** Where an entry or subsection is set in the parameter file: its file and line. */
      using Origins = std::map<std::string, std::string>;

      /** "'file' line N" of the expanded line @p line of @p file; empty for a built-in text. */
      std::string
      origin_of(const ExpandedFile &file, const unsigned int line)
      {
        if (line < 1 || line > file.origin.size())
          return "";
        const auto &[name, number] = file.origin[line - 1];
        return "'" + name + "' line " + std::to_string(number);
      }

      /**
       * A value of @p entry (a `Section/.../Entry` path), all of whose
       * numbers must be doubles: a number whose magnitude is beyond the
       * largest double or below the smallest normal one (1e400, 1e-320;
       * ParameterHandler lets the latter through and then "cannot convert"
       * it) is refused with the entry, its place @p where and the range allowed.
       */
      void
      check_number_range(const std::string &entry,
                         const std::string &value,
                         const std::string &where)
      {
        static const std::regex number(R"([-+]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][-+]?[0-9]+)?)");
        std::istringstream      items(std::regex_replace(value, std::regex("[,;:=]"), " "));
        for (std::string item; items >> item;)
          {
            if (!std::regex_match(item, number))
              continue;
            errno               = 0;
            const double parsed = std::strtod(item.c_str(), nullptr);
            if (errno != ERANGE)
              continue;
            std::ostringstream message;
            message << (where.empty() ? "" : where + ": ") << entry << " = " << value << ": "
                    << item << " is "
                    << (std::abs(parsed) > 1. ? "larger in magnitude than the largest double, "
                                              : "smaller in magnitude than the smallest normal "
                                                "double, ")
                    << (std::abs(parsed) > 1. ? std::numeric_limits<double>::max()
                                              : std::numeric_limits<double>::min())
                    << ". Write 0 or a number of magnitude between "
                    << std::numeric_limits<double>::min() << " and "
                    << std::numeric_limits<double>::max() << ".";
            throw InputError(message.str());
          }
      }

      /**
       * The place of each entry and subsection @p file sets (an entry's last
       * `set`, a subsection's first line), by its path; the numbers of every
       * entry but a function's expression (muparser's own syntax) checked by
       * check_number_range().
       */
      Origins
      scan_entries(const ExpandedFile &file)
      {
        Origins                  origins;
        std::vector<std::string> path;
        const auto               joined = [&path](const std::string &name) {
          std::string result;
          for (const auto &section : path)
            result += section + "/";
          return result + name;
        };
        for_each_statement(file.text, [&](const unsigned int line, const std::string &statement) {
          if (statement == "end" && !path.empty())
            path.pop_back();
          else if (const auto subsection = after_keyword(statement, "subsection"))
            {
              origins.emplace(joined(*subsection), origin_of(file, line));
              path.push_back(*subsection);
            }
          else if (const auto set = after_keyword(statement, "set");
                   set && set->find('=') != std::string::npos)
            {
              const std::string name  = Utilities::trim(set->substr(0, set->find('=')));
              const std::string value = Utilities::trim(set->substr(set->find('=') + 1));
              origins[joined(name)]   = origin_of(file, line);
              if (name != "Function expression")
                check_number_range(joined(name), value, origin_of(file, line));
            }
        });
        return origins;
      }

      /** The places of the entries of the parameter file parsed last (scan_entries()). */
      Origins entry_origins;
    } // namespace

    namespace
    {
      /**
       * ParameterHandler's message that a value does not match its entry's
       * pattern, as "'file' line N: Section/.../Entry = value: not allowed,
       * the entry takes <pattern>", with the entry's whole path; nothing for
       * other messages, or when the line set no entry scan_entries() found.
       */
      std::optional<std::string>
      entry_not_allowed(const std::string &message, const ExpandedFile &file)
      {
        static const std::regex mismatch(
            "Line <([0-9]+)>[\\s\\S]*The entry value\\s+([\\s\\S]*?)\\s+for the entry "
            "named\\s+([\\s\\S]*?)\\s+"
            "does not match the given pattern:\\s+([\\s\\S]*?)\\s*$");
        std::smatch match;
        if (!std::regex_search(message, match, mismatch))
          return std::nullopt;
        const std::string where = origin_of(file, std::stoul(match[1]));
        const std::string name  = "/" + match[3].str();
        for (const auto &[path, origin] : entry_origins)
          if (!where.empty() && origin == where && ("/" + path).size() >= name.size() &&
              ("/" + path).compare(path.size() + 1 - name.size(), name.size(), name) == 0)
            return where + ": " + path + " = " + match[2].str() +
                   ": not allowed; the entry takes " + match[4].str() + ".";
        return std::nullopt;
      }
    } // namespace

    std::string
    located(const std::string &message)
    {
      std::string origin;
      std::size_t longest = 0;
      for (const auto &[path, where] : entry_origins)
        if (path.size() > longest && message.rfind(path, 0) == 0 &&
            (message.size() == path.size() ||
             std::string(" :=").find(message[path.size()]) != std::string::npos))
          {
            longest = path.size();
            origin  = where;
          }
      return origin.empty() ? message : origin + ": " + message;
    }

    namespace
    {
      std::string parameter_file_directory = ".";
    }

    std::string
    input_path(const std::string &path)
    {
      if (path.empty() || std::filesystem::path(path).is_absolute() ||
          std::filesystem::exists(path))
        return path;
      return (std::filesystem::path(parameter_file_directory) / path).string();
    }

    template <int dim>
    ConditionSections
    parse(ParameterHandler &prm, const std::string &text, const bool is_file)
    {
      if (is_file)
        parameter_file_directory = std::filesystem::path(text).parent_path().string();
      if (parameter_file_directory.empty())
        parameter_file_directory = ".";
      const ExpandedFile content       = is_file ? read_file(text) : ExpandedFile{text, {}};
      entry_origins                    = scan_entries(content);
      const ConditionSections sections = condition_sections(content.text);
      StabilizedLagrangian::BoundaryConditions::declare_parameters<dim>(prm, sections);
      declare_contact_zones(prm, sections.zones);
      try
        {
          prm.parse_input_from_string(content.text);
        }
      catch (const ExceptionBase &e)
        {
          std::ostringstream message;
          e.print_info(message);
          throw InputError(entry_not_allowed(message.str(), content)
                               .value_or("Error in the parameter file " +
                                         (is_file ? "'" + text + "'" : std::string("(built-in)")) +
                                         ":\n" + locate(message.str(), content)));
        }
      return with_template(sections);
    }

    unsigned int
    read_dimension(const std::string &text, const bool is_file)
    {
      ParameterHandler prm;
      prm.declare_entry("Dimension",
                        "2",
                        Patterns::Integer(2, 3),
                        "2 (plane strain, or axisymmetric: Geometry/Axisymmetric) or 3.");
      const ExpandedFile content = is_file ? read_file(text) : ExpandedFile{text, {}};
      try
        {
          prm.parse_input_from_string(content.text, "", true);
        }
      catch (const ExceptionBase &e)
        {
          std::ostringstream message;
          e.print_info(message);
          throw InputError("Error in the parameter file '" + text +
                           "': " + locate(message.str(), content));
        }
      return prm.get_integer("Dimension");
    }

    template ConditionSections
    parse<2>(ParameterHandler &, const std::string &, const bool);
    template ConditionSections
    parse<3>(ParameterHandler &, const std::string &, const bool);
    template void
    declare_all<2>(ParameterHandler &);
    template void
    declare_all<3>(ParameterHandler &);
  } // namespace Parameters
} // namespace StabilizedLagrangian
