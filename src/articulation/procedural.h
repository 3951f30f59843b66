#pragma once
// The procedural articulation model: timed phones -> trajectories of the papers' ten EMA
// sensors at 50 fps, in the head frame (mm).
//
// Coarticulation in two steps, each for a reason:
//  1. Dominance blending (Cohen & Massaro 1993): every phone pulls each articulatory parameter
//     towards its target with a strength that is flat inside the phone and decays outside it.
//     This is what lets a phone's critical articulator win (the lips of /p/, the tip of /t/)
//     while uncommitted articulators take the shape of the neighbours (the tongue during /p/,
//     anticipatory lip rounding before /u/).
//  2. Second-order, critically damped target tracking per parameter (the point-attractor
//     dynamics of task dynamics, Saltzman & Munhall 1989): the blended target is a step
//     function in time; articulators have mass, so positions follow it smoothly with bell-
//     shaped velocity profiles and bounded peak speed. Each articulator has its own natural
//     frequency (the tongue tip is quicker than the jaw).
// Contacts (lip closure, tongue-palate closure) come from targets placed beyond the contact,
// which the vocal tract geometry stops at the surface, as real articulators press on.
#include <cstddef>

#include "articulation/vocal_tract.h"
#include "ema/landmarks.h"
#include "phones/phone_seq.h"

namespace glossa::articulation {

struct ProceduralOptions {
  double rate = 50.0;            // output frames per second
  double amplitude = 1.0;        // scales every target (speaker / style variation)
  double speed = 1.0;            // scales every articulator's natural frequency
  double reach = 0.04;           // s: how far a phone's dominance reaches outside it
  double rounding_reach = 0.09;  // s: the same for the lip targets of rounded phones
  // s: articulators move towards a phone's target this long before its acoustic onset, so that
  // the lagging dynamics reach a closure while the closure is heard.
  double lead = 0.03;
};

struct Articulation {
  LandmarkSeq landmarks;  // frames x 30, the papers' 10 sensors
  MatrixRM params;        // frames x kParamCount, the articulatory parameters
};

// Frame f is at time f / rate (the audio encoders' frame centres). Phones outside
// [0, frames / rate] are clipped; times not covered by a phone are silence.
// Throws glossa::Error on an invalid phone sequence.
Articulation articulate(const phones::PhoneSeq& phones, size_t frames,
                        const ProceduralOptions& options = {});

}  // namespace glossa::articulation
