#!/usr/bin/env bash
# SPDX-License-Identifier: AGPL-3.0-or-later
# Writes the seed corpus of request_fuzz (tests/fuzz/corpus/request_fuzz/):
# dot.v1.TriangulateRequest messages in protobuf text format, encoded by
# protoc. Run from anywhere; needs protobuf-compiler.
set -euo pipefail
cd "$(dirname "$0")/../.."
out=tests/fuzz/corpus/request_fuzz
mkdir -p "$out"
seed() {  # NAME TEXT
  protoc --proto_path=proto --encode=dot.v1.TriangulateRequest \
    dot/v1/triangulation.proto <<<"$2" >"$out/$1.pb"
}
seed square 'id: "square" polygon { coordinates: [0,0,0, 1,0,0, 1,1,0, 0,1,0] }'
seed skew_dot2 'id: "skew" polygon { coordinates: [0,0,0, 2,0,1, 2,2,0, 0,2,1, -1,1,0] }
  weights { area: 1 squared_dihedral: 0.5 }
  options { validate_output: true omit_input_vertices: true progress_interval_ms: 1 }'
seed normals 'polygon { coordinates: [0,0,0, 1,0,0, 1,1,0.5, 0,1,0]
  normals: [0,0,1, 0,0,1, 0,0,1, 0,0,1] }
  weights { normal_deviation: 1 shape: 0.25 perimeter: -1 }'
seed all_space 'polygon { coordinates: [0,0,0, 3,0,0, 3,3,0, 0,3,0, 1,1,2, 2,2,2] }
  weights { dihedral: 1 } options { search_space: SEARCH_SPACE_ALL no_cache: true }'
seed tetgen_protect 'polygon { coordinates: [0,0,0, 4,0,0, 4,4,1, 0,4,0, 2,2,3, 1,3,-2, 3,1,2] }
  options { search_space: SEARCH_SPACE_DELAUNAY protect_edges: true
            delaunay_backend: DELAUNAY_BACKEND_TETGEN time_budget_ms: 50
            memory_budget_bytes: 1000000 }'
seed partial_vertex 'polygon { coordinates: [0,0,0, 1,0,0, 1,1] }'
seed bad_enum 'polygon { coordinates: [0,0,0, 1,0,0, 0,1,0] } options { search_space: 7 delaunay_backend: 9 }'
seed duplicate 'polygon { coordinates: [0,0,0, 1,0,0, 0,0,0, 0,1,0] } weights { area: inf }'
