#pragma once

#include <stabilized_lagrangian/solver/state_archive.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace StabilizedLagrangian
{
  /**
   * @brief The run's state, listed once: every piece of it (the solution, the
   * contact points' states, the time, the material history, ...) is an entry
   * with a name, a way to write it into a StateWriter and a way to read it
   * back from a StateReader. The step-cut snapshot (taken before each attempt
   * of a load step, restored when the attempt fails) and the checkpoint
   * (written every `Output/Checkpoint interval` steps, read by `--resume`)
   * both go through this list, so a piece of state added here is kept by both.
   *
   * Reading is done in two parts, as a checkpoint is untrusted input read on
   * every rank: an entry's Load reads and checks its bytes (throwing an
   * InputError through StateReader::damaged()) and makes no collective call;
   * the function it returns puts the state into the run, and may be
   * collective. The list is open: anyone holding the run's RunState (a test,
   * an extension) can add an entry.
   */
  class RunState
  {
  public:
    /** @brief What keeps an entry. */
    enum class Scope
    {
      /** the step-cut snapshot and the checkpoint */
      step_cut_and_checkpoint,
      /**
       * the checkpoint only: a failed attempt leaves the entry as it was
       * (as the material history, whose trial values an attempt writes and
       * only a converged step commits), or changes it only once a step is
       * accepted (the load stepping, the output records)
       */
      checkpoint_only
    };
    /** @brief Write an entry's state. */
    using Save = std::function<void(StateWriter &)>;
    /**
     * @brief Read an entry's state and check it (no collective call); returns
     * what puts it into the run (may be collective; may be empty).
     */
    using Load = std::function<std::function<void()>(StateReader &)>;
    /** @brief A copy of an entry's state in memory; returns what puts it back. */
    using Keep = std::function<std::function<void()>()>;

    /** @brief One piece of the run's state. */
    struct Entry
    {
      std::string name;  ///< unique; names the entry in the checkpoint and in messages
      Scope       scope; ///< what keeps it
      Save        save;
      Load        load;
      /**
       * optional: the step cut's copy in memory, where that is cheaper than
       * the bytes of save (a distributed vector); empty: the step cut keeps
       * the bytes of save and reads them with load
       */
      Keep keep;
    };

    /**
     * @brief Add @p entry to the list (its place in the list is the order of
     * reading: an entry may rely on those added before it).
     */
    void
    add(const std::string &name, Scope scope, Save save, Load load, Keep keep = {});

    /**
     * @brief Add the entry @p name that keeps @p value (trivially copyable,
     * or a vector of such), checked by @p valid when read from a checkpoint.
     */
    template <typename T>
    void
    add_value(const std::string                    &name,
              T                                    &value,
              const Scope                           scope,
              const std::function<bool(const T &)> &valid = {});

    /** @brief A copy of @p value in memory, for Entry::keep. */
    template <typename T>
    static Keep
    copy_of(T &value)
    {
      return [&value]() -> std::function<void()> {
        auto copy = std::make_shared<const T>(value);
        return [&value, copy]() { value = *copy; };
      };
    }

    /** @brief The state a step cut puts back: the entries of Scope::step_cut_and_checkpoint. */
    class Snapshot
    {
    public:
      /** @brief Put the saved state back, in the list's order (collective). */
      void
      restore() const;

    private:
      friend class RunState;
      std::vector<std::function<void()>> restorers;
    };

    /** @brief Save the state of every step-cut entry (before an attempt of a load step). */
    Snapshot
    snapshot() const;

    /** @brief Write every checkpoint entry: their number, then each one's name and bytes. */
    void
    write(StateWriter &out) const;

    /**
     * @brief Read what write() wrote: the bytes of every checkpoint entry, in
     * the list's order. A checkpoint that lacks an entry of the list or holds
     * one the list does not have is refused (InputError).
     */
    std::vector<std::string>
    read_entries(StateReader &in) const;

    /**
     * @brief Read and check every checkpoint entry from its @p bytes (from
     * read_entries(); no collective call); returns what puts them into the
     * run, to be called in order (collective).
     * @param file the checkpoint file, named by the messages
     */
    std::vector<std::function<void()>>
    load(const std::vector<std::string> &bytes, const std::string &file) const;

  private:
    std::vector<Entry> entries;
  };

  template <typename T>
  void
  RunState::add_value(const std::string                    &name,
                      T                                    &value,
                      const Scope                           scope,
                      const std::function<bool(const T &)> &valid)
  {
    add(
        name,
        scope,
        [&value](StateWriter &out) { out.put(value); },
        [&value, name, valid](StateReader &in) -> std::function<void()> {
          T read{};
          if constexpr (std::is_trivially_copyable_v<T>)
            in.get(read);
          else
            in.get(read, name);
          if (valid && !valid(read))
            in.damaged("its " + name + " is not valid");
          return [&value, read]() { value = read; };
        },
        copy_of(value));
  }
} // namespace StabilizedLagrangian
