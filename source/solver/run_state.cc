#include <stabilized_lagrangian/solver/run_state.h>

#include <deal.II/base/exceptions.h>

#include <algorithm>
#include <map>

namespace StabilizedLagrangian
{
  void
  RunState::add(const std::string &name, Scope scope, Save save, Load load, Keep keep)
  {
    Entry entry{name, scope, std::move(save), std::move(load), std::move(keep)};
    AssertThrow(std::none_of(entries.begin(),
                             entries.end(),
                             [&](const Entry &e) { return e.name == entry.name; }),
                dealii::ExcMessage("the run's state has an entry '" + entry.name + "' already"));
    AssertThrow(entry.save && entry.load,
                dealii::ExcMessage("the entry '" + entry.name + "' needs a save and a load"));
    entries.push_back(std::move(entry));
  }

  void
  RunState::Snapshot::restore() const
  {
    for (const auto &restore_entry : restorers)
      restore_entry();
  }

  RunState::Snapshot
  RunState::snapshot() const
  {
    Snapshot saved;
    for (const Entry &entry : entries)
      {
        if (entry.scope != Scope::step_cut_and_checkpoint)
          continue;
        if (entry.keep)
          {
            saved.restorers.push_back(entry.keep());
            continue;
          }
        StateWriter out;
        entry.save(out);
        saved.restorers.push_back([bytes = out.bytes(), &entry]() {
          StateReader in(bytes, "(the state before the load step)");
          if (const auto put_back = entry.load(in))
            put_back();
        });
      }
    return saved;
  }

  void
  RunState::write(StateWriter &out) const
  {
    out.put(static_cast<std::uint64_t>(entries.size()));
    for (const Entry &entry : entries)
      {
        StateWriter bytes;
        entry.save(bytes);
        out.put(entry.name);
        out.put(bytes.bytes());
      }
  }

  std::vector<std::string>
  RunState::read_entries(StateReader &in) const
  {
    // (an entry takes at least the lengths of its name and of its bytes)
    const auto                         n = in.count("state entries", 2 * sizeof(std::uint64_t));
    std::map<std::string, std::string> found;
    for (std::uint64_t k = 0; k < n; ++k)
      {
        std::string name, bytes;
        in.get(name, 256, "the name of a state entry");
        in.get(bytes, std::string::npos, "the state '" + name + "'");
        if (!found.emplace(name, std::move(bytes)).second)
          in.damaged("it holds the state '" + name + "' twice");
      }
    std::vector<std::string> in_order;
    for (const Entry &entry : entries)
      {
        const auto bytes = found.find(entry.name);
        if (bytes == found.end())
          throw InputError("the checkpoint file " + in.file() + " holds no state '" + entry.name +
                           "', which this run keeps: it was written by another version of the "
                           "program or for another set of state. Start the run again without "
                           "--resume.");
        in_order.push_back(std::move(bytes->second));
        found.erase(bytes);
      }
    if (!found.empty())
      throw InputError("the checkpoint file " + in.file() + " holds the state '" +
                       found.begin()->first +
                       "', which this run does not keep: it was written by another version of "
                       "the program or for another set of state. Start the run again without "
                       "--resume.");
    return in_order;
  }

  std::vector<std::function<void()>>
  RunState::load(const std::vector<std::string> &bytes, const std::string &file) const
  {
    AssertDimension(bytes.size(), entries.size());
    std::vector<std::function<void()>> put_back;
    for (unsigned int k = 0; k < entries.size(); ++k)
      {
        StateReader in(bytes[k], file + " (its state '" + entries[k].name + "')");
        put_back.push_back(entries[k].load(in));
        if (!in.at_end())
          in.damaged("it holds more bytes than the state is made of");
      }
    return put_back;
  }
} // namespace StabilizedLagrangian
