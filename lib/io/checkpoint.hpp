#pragma once
// The state a killed or stopped run resumes from (/checkpoint,
// docs/output-format.md): the executor's positions, velocities and carried
// bytes (plan::PlanState) of the last recorded frame, and how many rows of
// every series belong to it.
// Two slots written in turn, each with a hash, so a kill in the middle of a
// write leaves the other slot whole.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "io/h5_handle.hpp"

namespace atssim::io {

struct Checkpoint {
  long long frame = -1;          // simulated frame the state is the end of (0: the initial state)
  long long frames_written = 0;  // rows of /frames and /timing that belong to it
  long long schedule_rows = 0;   // rows of /schedule/{frame,task,…}
  long long wait_rows = 0;       // rows of /schedule/waits/*
  long long makespan_rows = 0;   // rows of /schedule/makespan/*
  std::vector<std::byte> positions, velocities;
  std::vector<std::byte> carried;  // empty in a file written before atssim kept it
};

class CheckpointSlots {
 public:
  CheckpointSlots() = default;
  // Makes /checkpoint for states of these sizes.
  static CheckpointSlots create(hid_t file, std::size_t position_bytes, std::size_t velocity_bytes,
                                std::size_t carried_bytes = 0);
  // Opens the /checkpoint of a file written before; empty when it has none.
  static std::optional<CheckpointSlots> open(hid_t file);

  // Writes `c` into the slot not holding the newest checkpoint.
  void write(const Checkpoint& c);
  // The newest slot whose hash matches and whose rows do not exceed
  // `frames_available` frames; the other slot is emptied (a resumed run
  // writes over what came after) and is written next.
  std::optional<Checkpoint> take_newest(long long frames_available);
  // The same without changing the file (`slot_found`: which slot it was).
  std::optional<Checkpoint> newest(long long frames_available, int* slot_found = nullptr) const;

  bool valid() const { return state_.get() >= 0; }
  std::size_t carried_bytes() const { return carried_bytes_; }

 private:
  std::size_t state_bytes() const { return position_bytes_ + velocity_bytes_ + carried_bytes_; }
  H5Handle state_, index_;
  std::size_t position_bytes_ = 0, velocity_bytes_ = 0, carried_bytes_ = 0;
  int next_slot_ = 0;
};

}  // namespace atssim::io
