// Byte encoding of the mapper state and its parts (nodes, edges, estimates), shared by the
// snapshot file (mapper_state_io.h) and the journal records (mapper_store.h), in the common
// byte codec (persist/byte_codec.h). Decoding checks every count against a bound and every
// number for finiteness, and throws persist::CorruptBytes on anything else: a state that would poison
// the mapper is refused, never half-loaded.
#pragma once

#include "persist/byte_codec.h"
#include "scan_mapper/scan_mapper.h"

namespace rgnav::scan_mapper {

void write_node(persist::ByteWriter& w, const ScanNode& n);
ScanNode read_node(persist::ByteReader& r);  // normals are not stored: recomputed by the mapper
void write_edge(persist::ByteWriter& w, const PoseGraphEdge& e);
PoseGraphEdge read_edge(persist::ByteReader& r, uint64_t node_count);  // ends must be < node_count

// The parts of a node that change after it was added: estimate, covariance, publication.
void write_estimate(persist::ByteWriter& w, const ScanNode& n);
void read_estimate(persist::ByteReader& r, ScanNode* n);

// Throws persist::CorruptBytes if a pose or covariance of the state is not finite: such a state is
// never written (it would be reloaded into every later run).
void check_finite(const MapperState& state);
void check_finite(const ScanNode& node);

}  // namespace rgnav::scan_mapper
