// Primitive assembly order with the provoking vertex first (draw_decompose_tmp.h, lp_setup_vbuf.c),
// and the driver's draw chunks with their "pipelined" flag (draw_chunks.hpp, docs/lavapipe-rules.md §1.5).
#include <array>

#include <gtest/gtest.h>

#include "cpu_raster/exact/assemble.hpp"
#include "cpu_raster/exact/draw_chunks.hpp"

namespace rastercmp::cpu {
namespace {

Draw draw_of(Topology topology, uint32_t vertices) {
  Draw draw;
  draw.topology = topology;
  draw.positions_clip.resize(vertices, glm::vec4(0, 0, 0, 1));
  return draw;
}

std::array<uint32_t, 3> vertices_of(const Draw& draw, uint32_t i) { return assemble_primitive(draw, i).position; }

TEST(CpuAssemble, TriangleStripAlternatesTheLastTwoVertices) {
  const Draw strip = draw_of(Topology::TriangleStrip, 6);
  ASSERT_EQ(primitive_count(strip), 4u);
  EXPECT_EQ(vertices_of(strip, 0), (std::array<uint32_t, 3>{0, 1, 2}));
  EXPECT_EQ(vertices_of(strip, 1), (std::array<uint32_t, 3>{1, 3, 2}));
  EXPECT_EQ(vertices_of(strip, 2), (std::array<uint32_t, 3>{2, 3, 4}));
  EXPECT_EQ(vertices_of(strip, 3), (std::array<uint32_t, 3>{3, 5, 4}));
}

TEST(CpuAssemble, TriangleFanPutsTheHubLast) {
  const Draw fan = draw_of(Topology::TriangleFan, 5);
  ASSERT_EQ(primitive_count(fan), 3u);
  EXPECT_EQ(vertices_of(fan, 0), (std::array<uint32_t, 3>{1, 2, 0}));
  EXPECT_EQ(vertices_of(fan, 2), (std::array<uint32_t, 3>{3, 4, 0}));
}

TEST(CpuAssemble, ListsAndLineStrips) {
  const Draw list = draw_of(Topology::TriangleList, 7);  // the incomplete 7th vertex is ignored
  EXPECT_EQ(primitive_count(list), 2u);
  EXPECT_EQ(vertices_of(list, 1), (std::array<uint32_t, 3>{3, 4, 5}));
  const Draw lines = draw_of(Topology::LineList, 5);
  EXPECT_EQ(primitive_count(lines), 2u);
  EXPECT_EQ(assemble_primitive(lines, 1).position[0], 2u);
  EXPECT_EQ(assemble_primitive(lines, 1).position[1], 3u);
  EXPECT_EQ(assemble_primitive(lines, 1).vertex_count, 2u);
  const Draw strip = draw_of(Topology::LineStrip, 4);
  EXPECT_EQ(primitive_count(strip), 3u);
  EXPECT_EQ(assemble_primitive(strip, 2).position[0], 2u);
  EXPECT_EQ(assemble_primitive(strip, 2).position[1], 3u);
}

TEST(CpuAssemble, IndicesAreResolvedAndNameThePrimitive) {
  Draw strip = draw_of(Topology::TriangleStrip, 10);
  strip.indices = {9, 8, 7, 6};
  ASSERT_EQ(primitive_count(strip), 2u);
  const AssembledPrimitive second = assemble_primitive(strip, 1);
  EXPECT_EQ(second.primitive_index, 1u);
  EXPECT_EQ(second.position, (std::array<uint32_t, 3>{8, 6, 7}));
}

TEST(CpuAssemble, TooFewVerticesFormNoPrimitive) {
  EXPECT_EQ(primitive_count(draw_of(Topology::TriangleStrip, 2)), 0u);
  EXPECT_EQ(primitive_count(draw_of(Topology::TriangleFan, 1)), 0u);
  EXPECT_EQ(primitive_count(draw_of(Topology::LineStrip, 1)), 0u);
}

TEST(CpuDrawChunks, PrimitivesPerChunkFollowTheSegmentSize) {
  Draw draw = draw_of(Topology::TriangleList, 3);
  EXPECT_EQ(primitives_per_chunk(draw), 1365u);  // 4095 of 4096 vertices: whole triangles
  draw.indices = {0, 1, 2};
  EXPECT_EQ(primitives_per_chunk(draw), 341u);  // 1023 of 1024 indices
  draw.topology = Topology::TriangleStrip;
  EXPECT_EQ(primitives_per_chunk(draw), 1022u);  // segments overlap by two vertices
  draw.topology = Topology::TriangleFan;
  EXPECT_EQ(primitives_per_chunk(draw), 1022u);
  draw.indices.clear();
  EXPECT_EQ(primitives_per_chunk(draw), 4094u);
}

TEST(CpuDrawChunks, OnlyTheChunkThatUsesAClippedVertexIsPipelined) {
  // 400 indexed triangles = chunks of 341 and 59; only triangle 350 uses position 5 (outside x).
  Draw draw = draw_of(Topology::TriangleList, 6);
  draw.positions_clip[5] = glm::vec4(2, 0, 0, 1);
  for (uint32_t t = 0; t < 400; ++t) {
    const uint32_t last = t == 350 ? 5u : 2u;
    draw.indices.insert(draw.indices.end(), {0, 1, last});
  }
  EXPECT_EQ(pipelined_chunks(draw, true), (std::vector<bool>{false, true}));
  draw.indices[3 * 350 + 2] = 2;  // position 5 still exists but no primitive uses it
  EXPECT_EQ(pipelined_chunks(draw, true), (std::vector<bool>{false, false}));
}

TEST(CpuDrawChunks, AFanHubOutsideMakesEveryChunkPipelined) {
  Draw fan = draw_of(Topology::TriangleFan, 5000);  // 4998 triangles: chunks of 4094 and 904
  EXPECT_EQ(pipelined_chunks(fan, true), (std::vector<bool>{false, false}));
  fan.positions_clip[0] = glm::vec4(0, 0, -1, 1);  // z < 0: outside the near plane
  EXPECT_EQ(pipelined_chunks(fan, true), (std::vector<bool>{true, true}));
  EXPECT_EQ(pipelined_chunks(fan, false), (std::vector<bool>{false, false}));  // depth clip off
}

}  // namespace
}  // namespace rastercmp::cpu
