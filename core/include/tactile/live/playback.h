#pragma once
// Replay clock: where the time cursor is, whether it moves, and how fast.

namespace tactile {

class PlaybackClock {
 public:
  static constexpr double kMinSpeed = 0.25;
  static constexpr double kMaxSpeed = 4.0;

  void set_range(double start, double end);
  // Moves the cursor by `seconds` of wall time times the speed when playing; stops at
  // the end (and stays there) unless looping.
  void advance(double seconds);
  void seek(double time);  // clamped to the range
  void play();
  void pause();
  void toggle() { playing_ ? pause() : play(); }
  // Clamped to [kMinSpeed, kMaxSpeed].
  void set_speed(double speed);

  double time() const { return time_; }
  double speed() const { return speed_; }
  bool playing() const { return playing_; }
  bool looping() const { return looping_; }
  void set_looping(bool looping) { looping_ = looping; }
  double start() const { return start_; }
  double end() const { return end_; }

 private:
  double start_ = 0.0;
  double end_ = 0.0;
  double time_ = 0.0;
  double speed_ = 1.0;
  bool playing_ = false;
  bool looping_ = false;
};

}  // namespace tactile
