// The scenario of paper 003 (Table I) played by one subject: stage commands, what the
// subject does after each, and the robot's own gestures while it speaks.

#include "robovie_scenario.h"

#include <algorithm>
#include <cmath>

#include "robovie_gestures.h"
#include "tactile/error.h"

namespace tactile::sim::robovie {

namespace {

// Table I, in order; the scripts below are indexed by these stages.
enum Stage {
  kHello,
  kShakeHands,
  kNiceToMeetYou,
  kWhatsYourName,
  kWhereFrom,
  kLetsPlay,
  kCute,
  kPatHead,
  kWhee,
  kPlayMore,
  kTickleMe,
  kThatTickles,
  kThanks,
  kHug,
  kByeBye,
  kStageCount
};

// How long the robot takes to say a stage's line: a child's voice, ~0.3 s per word.
double speech_time(const std::string& line) {
  int words = 1;
  for (char c : line) words += c == ' ';
  return 0.5 + 0.3 * words;
}

// How long the subject talks back (s, before patience): longest for the questions.
double answer_time(int stage, Random& random) {
  switch (stage) {
    case kWhatsYourName:
      return random.uniform(2.0, 5.0);
    case kWhereFrom:
      return random.uniform(3.0, 8.0);
    case kNiceToMeetYou:
    case kCute:
      return random.uniform(1.5, 4.0);
    default:
      return random.uniform(1.0, 3.0);
  }
}

const char* const kPartsOfApproach[] = {"chest-upper", "upper-arm-right", "upper-arm-left"};

class SessionPlayer {
 public:
  SessionPlayer(const Films& films, const Habits& habits, Random& random, Session& session)
      : habits_(habits),
        random_(random),
        session_(session),
        hands_(films, habits, random, session) {}

  // The subject's response to stage `stage` starting at `t`; returns when it is done.
  double respond(int stage, double t) {
    const View front = View::kFront;
    const MapArea approach_part =
        hands_.area(kPartsOfApproach[static_cast<int>(session_.approach)], front);
    switch (stage) {
      case kHello:
        if (random_.chance(0.4 + 0.5 * habits_.touchiness))
          return random_.chance(0.5) ? hands_.hold(t, approach_part, 5.0, random_.uniform(1.0, 2.0))
                                     : hands_.tap(hands_.tap(t, approach_part, 5.0, false) + 0.3,
                                                  approach_part, 5.0, false);
        return t;
      case kShakeHands: {
        // Draws in their own statements: the order of a call's arguments is unspecified.
        const int pumps = static_cast<int>(random_.integer(2, 6));
        const double hold_after = random_.chance(0.6) ? random_.uniform(0.5, 4.0) : 0.0;
        return hands_.hand_shake(t, pumps, hold_after);
      }
      case kNiceToMeetYou:
        if (random_.chance(0.5 * habits_.touchiness))
          return hands_.tap(t + random_.uniform(0.5, 2.0), approach_part, 4.0, false);
        return t;
      case kWhatsYourName:
      case kWhereFrom:
        if (random_.chance(0.35 * habits_.touchiness)) {
          const char* forearm = random_.chance(0.5) ? "forearm-right" : "forearm-left";
          const double onset = t + random_.uniform(0.5, 2.0);
          return hands_.hold(onset, hands_.area(forearm, front), 3.0, random_.uniform(1.0, 4.0));
        }
        return t;
      case kLetsPlay:
        return play(t, random_.chance(0.85) ? habits_.play_style : random_.integer(0, 2), 1.0);
      case kCute:
        return cute(t);
      case kPatHead: {
        const MapArea head = hands_.area("head", View::kBack);
        const int count = std::max(2, habits_.pat_count + static_cast<int>(random_.integer(-1, 1)));
        double end = habits_.strokes_head
                         ? hands_.strokes(t, head, static_cast<int>(random_.integer(2, 4)))
                         : hands_.pats(t, head, count);
        if (random_.chance(0.15)) end = hands_.pats(end + 0.3, head, 2);
        return end;
      }
      case kWhee:
        switch (random_.chance(0.8) ? habits_.whee_style : random_.integer(0, 2)) {
          case 0:
            return hands_.swing_hands(t, random_.uniform(2.0, 4.0) * habits_.patience, 0.35);
          case 1:
            return hands_.lift_by_sides(t);
          default:
            return hands_.high_fives(t, static_cast<int>(random_.integer(3, 5)));
        }
      case kPlayMore:
        if (random_.chance(0.3 + 0.5 * habits_.touchiness)) return play(t, habits_.play_style, 0.5);
        return t;
      case kTickleMe: {
        const double tickling = random_.uniform(3.0, 9.0) * habits_.patience;
        tickle_until_ = hands_.tickle(t, tickling);
        // The robot laughs "That tickles!" soon after the fingers start.
        return std::min(tickle_until_, t + random_.uniform(1.2, 2.5));
      }
      case kThatTickles: {
        double end = std::max(t, tickle_until_);
        if (random_.chance(0.3 + 0.4 * habits_.touchiness)) {
          const double onset = end + random_.uniform(0.5, 1.5);
          end = hands_.tickle(onset, random_.uniform(1.0, 3.0));
        }
        return end;
      }
      case kThanks:
        if (random_.chance(0.5 * habits_.touchiness)) {
          const char* part = random_.chance(0.5) ? "head" : "shoulder-right";
          return hands_.pats(t, hands_.area(part, View::kBack),
                             static_cast<int>(random_.integer(1, 2)));
        }
        return t;
      case kHug: {
        const double onset = t + random_.uniform(0.5, 1.5);
        return hands_.hug(onset, random_.uniform(2.0, 6.0) * habits_.patience);
      }
      case kByeBye:
        switch (random_.chance(0.7) ? habits_.bye_style : random_.integer(0, 3)) {
          case 0:
            return hands_.hand_shake(t, static_cast<int>(random_.integer(1, 3)), 0.0);
          case 1:
            return hands_.pats(t, hands_.area("head", View::kBack),
                               static_cast<int>(random_.integer(2, 3)));
          case 2: {
            const double onset = t + random_.uniform(0.3, 1.0);
            return hands_.hug(onset, random_.uniform(1.0, 2.0));
          }
          default:
            return t;  // waves goodbye from where they stand
        }
      default:
        return t;
    }
  }

  // The subject's turn-on touch (rule 3 of Sec. IV-C) on the part nearest their approach.
  double turn_on(double t) {
    const MapArea part =
        hands_.area(kPartsOfApproach[static_cast<int>(session_.approach)], View::kFront);
    return hands_.hold(t, part, 6.0, random_.uniform(0.4, 1.2));
  }

 private:
  double play(double t, int64_t style, double scale) {
    switch (style) {
      case 0:
        return hands_.pokes(t, std::max(2, static_cast<int>(random_.integer(3, 7) * scale)));
      case 1:
        return hands_.swing_hands(t, random_.uniform(2.0, 4.0) * habits_.patience * scale, 0.25);
      default:
        return hands_.high_fives(t, std::max(2, static_cast<int>(random_.integer(2, 4) * scale)));
    }
  }

  double cute(double t) {
    switch (habits_.cute_style) {
      case 0:
        return hands_.strokes(t, hands_.area("head", View::kBack),
                              static_cast<int>(random_.integer(1, 3)));
      case 1:
        return hands_.cheeks(t);
      case 2:
        return hands_.pats(t, hands_.area("head", View::kBack),
                           static_cast<int>(random_.integer(2, 3)));
      default:
        return t;  // just says "yes"
    }
  }

  const Habits& habits_;
  Random& random_;
  Session& session_;
  Hands hands_;
  double tickle_until_ = 0.0;
};

// The robot's own movement for each stage's line: its program, the same in every trial
// (Wizard of Oz: the operator sends the stage, the robot plays it). Paper 003 says only that
// the data "includes lots of information caused by the robot movements" (Sec. V); which
// movement goes with which line is an estimate in the manner of Robovie's child-like
// behaviours (docs/SIMULATION.md). The lines that only talk get the small gestures of
// talking, drawn anew each time (below); the paper's classifiers recognise those stages least
// (Figs 8-9), the ones with a movement of their own (hello, play, cute, whee, bye-bye) best,
// touch or not. Times are seconds after the command; angles in rad.
struct ScriptedMove {
  Joint joint;
  JointMove::Shape shape;
  double delay, duration, amplitude, frequency_hz;
};

const std::vector<ScriptedMove>& stage_moves(int stage) {
  using S = JointMove::Shape;
  constexpr Joint kR = Joint::kRightArm, kL = Joint::kLeftArm, kH = Joint::kHead,
                  kW = Joint::kWaist;
  static const std::vector<ScriptedMove> kMoves[kStageCount] = {
      // "Hello.": raises the right hand and waves.
      {{kR, S::kBump, 0.2, 3.0, 1.0, 0}, {kR, S::kOscillation, 0.9, 1.6, 0.25, 1.5}},
      // "Let's shake hands.": holds out the right hand, takes it back later.
      {{kR, S::kRamp, 0.3, 1.2, 0.7, 0}, {kR, S::kRamp, 6.0, 1.2, -0.7, 0}},
      {},  // "Nice to meet you.": talking (below)
      {},  // "What's your name?"
      {},  // "Where are you from?"
      // "Let's play!": both arms up and down twice.
      {{kR, S::kBump, 0.2, 1.0, 0.7, 0},
       {kL, S::kBump, 0.2, 1.0, 0.7, 0},
       {kR, S::kBump, 1.3, 1.0, 0.7, 0},
       {kL, S::kBump, 1.3, 1.0, 0.7, 0}},
      // "Do you think I'm cute?": sways its head and body.
      {{kH, S::kOscillation, 0.2, 2.5, 0.15, 0.8}, {kW, S::kBump, 0.2, 2.5, 0.15, 0}},
      // "I wish you'd pat me on the head.": bows the head and holds it there.
      {{kH, S::kRamp, 0.3, 1.0, 0.35, 0}, {kH, S::kRamp, 5.0, 1.0, -0.35, 0}},
      // "Whee!": both arms high, the waist swaying.
      {{kR, S::kBump, 0.1, 2.2, 1.2, 0},
       {kL, S::kBump, 0.1, 2.2, 1.2, 0},
       {kW, S::kOscillation, 0.3, 2.0, 0.12, 1.0}},
      {},  // "I want to play more.": talking
      // "Tickle me.": lifts both arms to open its sides, lowers them later.
      {{kR, S::kRamp, 0.2, 1.0, 0.8, 0},
       {kL, S::kRamp, 0.2, 1.0, 0.8, 0},
       {kR, S::kRamp, 4.0, 1.0, -0.8, 0},
       {kL, S::kRamp, 4.0, 1.0, -0.8, 0}},
      {},  // "That tickles!": talking
      {},  // "Thanks"
      // "Give me a hug.": opens its arms, closes them around the person later.
      {{kR, S::kRamp, 0.2, 1.2, 0.9, 0},
       {kL, S::kRamp, 0.2, 1.2, 0.9, 0},
       {kR, S::kRamp, 5.0, 1.2, -0.9, 0},
       {kL, S::kRamp, 5.0, 1.2, -0.9, 0}},
      // "Bye-bye!": raises the right hand and waves longer.
      {{kR, S::kBump, 0.2, 3.5, 1.0, 0}, {kR, S::kOscillation, 0.9, 2.2, 0.3, 1.5}},
  };
  return kMoves[stage];
}

// While it only talks, the robot moves an arm or its head a little, differently each time.
void add_talking_gesture(Session& session, double command, Random& random) {
  if (!random.chance(0.85)) return;
  const double onset = command + random.uniform(0.1, 0.5);
  const double duration = random.uniform(0.8, 1.8);
  const double amplitude = random.uniform(0.2, 0.6);
  const double which = random.uniform();
  // One arm (right more often), both arms, or a nod of the head.
  if (which >= 0.8) {
    session.moves.push_back(
        {Joint::kHead, JointMove::Shape::kBump, onset, duration, 0.4 * amplitude});
    return;
  }
  if (which < 0.35 || which >= 0.6)
    session.moves.push_back(
        {Joint::kRightArm, JointMove::Shape::kBump, onset, duration, amplitude});
  if (which >= 0.35)
    session.moves.push_back({Joint::kLeftArm, JointMove::Shape::kBump, onset, duration, amplitude});
}

// The robot's own movements: it turns to the subject, plays each stage's movement while it
// speaks, and looks around; none of it depends on what the subject does.
void add_robot_gestures(Session& session, Random& random) {
  const double turn = session.approach == Approach::kFront   ? 0.0
                      : session.approach == Approach::kRight ? 0.5
                                                             : -0.5;
  const double first = session.commands.front();
  session.moves.push_back({Joint::kWaist, JointMove::Shape::kRamp, std::max(0.0, first - 2.5), 1.5,
                           turn * random.uniform(0.8, 1.2)});
  session.moves.push_back({Joint::kHead, JointMove::Shape::kRamp, std::max(0.0, first - 2.2), 1.0,
                           0.5 * turn * random.uniform(0.8, 1.2)});
  for (size_t stage = 0; stage < session.commands.size(); ++stage) {
    // The same program each time; the servos' timing and reach vary a little (one reach per
    // stage, so that a hold given back returns exactly to where it started).
    const double command = session.commands[stage] + random.uniform(0.0, 0.2);
    const double reach = random.uniform(0.9, 1.1);
    const double next =
        stage + 1 < session.commands.size() ? session.commands[stage + 1] : session.end;
    const std::vector<ScriptedMove>& program = stage_moves(static_cast<int>(stage));
    if (program.empty()) {
      add_talking_gesture(session, command, random);
      continue;
    }
    for (const ScriptedMove& move : program) {
      double onset = command + move.delay * random.uniform(0.9, 1.1);
      // A hold is given back before the next line at the latest.
      if (move.shape == JointMove::Shape::kRamp && move.amplitude < 0.0)
        onset = std::min(onset, std::max(command, next - move.duration - 0.2));
      session.moves.push_back({move.joint, move.shape, onset,
                               move.duration * random.uniform(0.9, 1.1), move.amplitude * reach,
                               move.frequency_hz});
    }
  }
  // Talking on, it keeps moving its arms now and then.
  for (double t = random.uniform(3.0, 10.0); t < session.end - 2.0; t += random.uniform(4.0, 14.0))
    session.moves.push_back({random.chance(0.5) ? Joint::kRightArm : Joint::kLeftArm,
                             JointMove::Shape::kBump, t, random.uniform(0.8, 1.6),
                             random.uniform(0.1, 0.4)});
  // Looking around: small head turns at random moments (about one every 8 s).
  for (double t = random.uniform(2.0, 8.0); t < session.end - 1.5; t += random.uniform(3.0, 13.0))
    session.moves.push_back({Joint::kHead, JointMove::Shape::kBump, t, random.uniform(0.6, 1.2),
                             random.uniform(-0.2, 0.2)});
}

}  // namespace

Habits draw_habits(uint64_t seed, int subject) {
  Random random(derive_engine(seed, "robovie-subject", subject));
  Habits habits;
  habits.force = std::clamp(random.normal(1.0, 0.3), 0.45, 1.8);
  habits.tempo = random.truncated_normal(1.0, 0.18, 2.0);
  habits.patience = random.truncated_normal(1.0, 0.25, 2.0);
  habits.touchiness = random.uniform(0.1, 0.7);
  habits.hand_size = random.truncated_normal(1.0, 0.1, 2.0);
  habits.reach = {random.normal(0.0, 12.0), random.normal(0.0, 12.0)};
  habits.hug_height = random.normal(0.0, 40.0);
  habits.two_handed_shake = random.chance(0.3);
  habits.strokes_head = random.chance(0.25);
  habits.pats_while_hugging = random.chance(0.4);
  habits.pat_count = static_cast<int>(random.integer(3, 8));
  habits.fingers = static_cast<int>(random.integer(2, 4));
  habits.tickle_hz = random.uniform(4.0, 8.0);
  habits.tickle_front = random.uniform(0.4, 1.0);
  habits.tickle_belly = random.uniform(0.0, 40.0);
  habits.play_style = static_cast<int>(random.integer(0, 2));
  habits.cute_style = static_cast<int>(random.integer(0, 3));
  habits.whee_style = static_cast<int>(random.integer(0, 2));
  habits.bye_style = static_cast<int>(random.integer(0, 3));
  return habits;
}

const char* approach_name(Approach approach) {
  switch (approach) {
    case Approach::kFront:
      return "front";
    case Approach::kRight:
      return "right";
    case Approach::kLeft:
      return "left";
  }
  return "front";
}

Session play_session(const Films& films, const std::vector<std::string>& stages,
                     const Habits& habits, uint64_t seed, int subject, int trial) {
  if (stages.size() != kStageCount)
    throw Error("layout classes", "the Robovie scenario has " + std::to_string(kStageCount) +
                                      " stages (Table I), the layout lists " +
                                      std::to_string(stages.size()));
  Random random(derive_engine(seed, "robovie-trial", subject, trial));
  Session session;
  // Each subject starts once from each of the three positions, in an order of their own.
  session.approach = static_cast<Approach>((subject + trial) % 3);
  SessionPlayer player(films, habits, random, session);

  // Walking 2 m up to the robot, then the turn-on touch; the operator starts the scenario.
  const double arrival = random.uniform(2.5, 4.5);
  player.turn_on(arrival);
  double command = arrival + random.uniform(0.5, 1.2);
  double done = command;
  for (int stage = 0; stage < kStageCount; ++stage) {
    session.commands.push_back(command);
    const double response = command + speech_time(stages[stage]) + random.uniform(0.4, 1.0);
    const double touched = player.respond(stage, response);
    const double answered = response + answer_time(stage, random) * habits.patience;
    // The robot chats on to keep the subject engaged ("approaching a person", Table I); the
    // operator watches, then sends the next line (Wizard of Oz, Sec. IV-C).
    // Where it asked for a touch it moves on once the touch is done; "That tickles!" comes
    // while the fingers are still at work.
    const bool asked_touch = stage == kShakeHands || stage == kPatHead || stage == kHug;
    if (stage == kTickleMe)
      done = touched + random.uniform(0.3, 0.8);
    else {
      const double chat = random.uniform(asked_touch ? 0.3 : 1.0, asked_touch ? 2.0 : 6.0);
      done = std::max(touched, answered) + chat + random.uniform(0.5, 2.0);
    }
    command = done;
  }
  double last_touch = 0.0;
  for (const Contact& contact : session.contacts) last_touch = std::max(last_touch, contact.end());
  session.end = std::max(done + random.uniform(2.0, 4.0), last_touch + 1.0);

  Random motion(derive_engine(seed, "robovie-motion", subject, trial));
  add_robot_gestures(session, motion);
  return session;
}

}  // namespace tactile::sim::robovie
