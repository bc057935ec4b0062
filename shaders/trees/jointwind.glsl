// Wind on the joints (sylva/trees/JointWind.hpp): the step of one joint's spring and the joint frames' algebra.
// Each function is the twin of one in engine/trees/src/JointWind.cpp, operation for operation.
#pragma once

#include "../shared/Trees.h"
#include "../common/wind.glsl"

/** One step of one joint (stepJoint in C++): θ and ω in, θ' and ω' out (xy: θ, zw: ω). */
vec4 jointWindStep(TreeJointRest r, vec4 m, WindUniforms wind, float dt, float maxBend) {
  if ((r.info.w & SYLVA_TREE_WIND_FIXED) != 0u) {
    return vec4(0.0);
  }
  float stop = maxBend * (float(r.info.w >> 16u) * (1.0 / 65535.0));
  wind.flow.w = wind.flow.w + r.spring.w;
  vec2 u = windVelocity(wind, r.probe.xy);
  float speed = sqrt(u.x * u.x + u.y * u.y);
  vec2 drive = u * speed;
  vec2 accel = vec2(r.torque.x * drive.x + r.torque.y * drive.y, r.torque.z * drive.x + r.torque.w * drive.y);
  float kI = r.spring.x;
  float cI = r.spring.y;
  vec2 theta = m.xy;
  vec2 omega = m.zw;
  float denom = 1.0 + dt * cI + dt * dt * kI;
  vec2 omega1 = (omega + dt * (accel - kI * theta)) / denom;
  vec2 theta1 = theta + dt * omega1;
  float square = theta1.x * theta1.x + theta1.y * theta1.y;
  if (square > stop * stop) {
    float len = sqrt(square);
    vec2 dir = theta1 / len;
    theta1 = dir * stop;
    float outward = omega1.x * dir.x + omega1.y * dir.y;
    if (outward > 0.0) {
      omega1 = omega1 - dir * outward;
    }
  }
  return vec4(theta1, omega1);
}

/** local · R(bend) · bone scale as rows (localFrame in C++); a base joint's frame is its rest frame. */
JointFrame jointLocalFrame(TreeJointRest r, vec2 bend) {
  if ((r.info.w & SYLVA_TREE_WIND_FIXED) != 0u) {
    return r.local;
  }
  float s = r.spring.z;
  vec3 r0 = vec3(s, 0.0, 0.0);
  vec3 r1 = vec3(0.0, s, 0.0);
  vec3 r2 = vec3(0.0, 0.0, s);
  float angle = sqrt(bend.x * bend.x + bend.y * bend.y);
  if (angle > 0.0) {
    float kx = bend.x / angle;
    float kz = bend.y / angle;
    float c = cos(angle);
    float sn = sin(angle);
    float t = 1.0 - c;
    r0 = vec3(c + t * kx * kx, -sn * kz, t * kx * kz) * s;
    r1 = vec3(sn * kz, c, -sn * kx) * s;
    r2 = vec3(t * kx * kz, sn * kx, c + t * kz * kz) * s;
  }
  JointFrame f;
  f.x = vec4(r.local.x.x * r0 + r.local.x.y * r1 + r.local.x.z * r2, r.local.x.w);
  f.y = vec4(r.local.y.x * r0 + r.local.y.y * r1 + r.local.y.z * r2, r.local.y.w);
  f.z = vec4(r.local.z.x * r0 + r.local.z.y * r1 + r.local.z.z * r2, r.local.z.w);
  return f;
}

vec4 composeRow(vec4 r, JointFrame b) {
  return r.x * b.x + r.y * b.y + r.z * b.z + vec4(0.0, 0.0, 0.0, r.w);
}

/** a · b for frames as rows (compose in C++). */
JointFrame composeFrames(JointFrame a, JointFrame b) {
  JointFrame f;
  f.x = composeRow(a.x, b);
  f.y = composeRow(a.y, b);
  f.z = composeRow(a.z, b);
  return f;
}
