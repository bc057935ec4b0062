// Integer hashes shared by shaders, each the twin of a C++ function so CPU references compute the same bits.
#pragma once

// Chris Wellons' lowbias32 (sylva::lowbias32 in engine/core/include/sylva/core/Random.hpp).
uint lowbias32(uint x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}
