#version 450 core
#include "algorithms/adaptive_transparency/bindings.h"
// Pass 1 of adaptive transparency (Salvi, Montgomery & Lefohn 2011): build
// each pixel's visibility function in its ordered critical section. A
// fragment (z, a) adds a node at z whose T is the visibility just in front
// of z times (1 - a), and multiplies every node behind z by (1 - a). When
// that makes slots.k + 1 nodes, the node whose removal changes the area under
// the visibility step function least is removed (section 4): removing node
// i lets T_(i-1) extend over [z_i, z_(i+1)), an area change of
// (T_(i-1) - T_i)(z_(i+1) - z_i). The last node is never a candidate, so
// the total transmittance stays exact.
#define OIT_ORDERED_LOCK_BINDING ADAPTIVE_TRANSPARENCY_LOCKS_BINDING
#include "shaders/ordered_access.glsl"
#include "shaders/shading.glsl"
#include "algorithms/adaptive_transparency/avf_storage.glsl"

void remove_smallest_area_node(uint first, uint count) {
  uint victim = 0u;
  float smallest = 1.0 / 0.0;
  float previous_t = 1.0;
  for (uint i = 0u; i + 1u < count; ++i) {
    const vec2 node = avf_nodes[first + i];
    const float area = (previous_t - node.y) * (avf_nodes[first + i + 1u].x - node.x);
    if (area < smallest) {
      smallest = area;
      victim = i;
    }
    previous_t = node.y;
  }
  for (uint i = victim; i + 1u < count; ++i) avf_nodes[first + i] = avf_nodes[first + i + 1u];
  atomicAdd(avf_removals, 1u);
}

// Adds the fragment to the function; a full function has one spare node
// (slots.k + 1 allocated per pixel) that the compression frees again.
void insert_node(uint pixel, float depth, float alpha) {
  const uint first = pixel * uint(slots.k + 1);
  const uint count = avf_counts[pixel];
  uint slot = count;
  while (slot > 0u && avf_nodes[first + slot - 1u].x > depth) {
    const vec2 behind = avf_nodes[first + slot - 1u];
    avf_nodes[first + slot] = vec2(behind.x, behind.y * (1.0 - alpha));
    --slot;
  }
  const float in_front = slot > 0u ? avf_nodes[first + slot - 1u].y : 1.0;
  avf_nodes[first + slot] = vec2(depth, in_front * (1.0 - alpha));
  if (count + 1u > uint(slots.k)) {
    remove_smallest_area_node(first, count + 1u);
    avf_counts[pixel] = count;
  } else {
    avf_counts[pixel] = count + 1u;
  }
}

void main() {
  const float alpha = oit_shade().a;
  const float depth = oit_view_depth();
  const uint pixel = slots_pixel();
  OIT_ORDERED(pixel, if (alpha > 0.0) insert_node(pixel, depth, alpha))
}
