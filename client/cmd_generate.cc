// SPDX-License-Identifier: AGPL-3.0-or-later
// dotctl generate curve|loops|hole|holes : test data. Polygons (the paper's
// curves, two loops bounding one surface, and hole boundaries grown on a
// triangle mesh) as "x y z [nx ny nz]" text; meshes with holes cut out (and
// the removed patches).
#include <CLI/CLI.hpp>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include "cli/json_envelope.h"
#include "commands.h"
#include "exit_codes.h"

namespace dot::client {

void AddGenerateHolesCommand(CLI::App* gen, Context* ctx);

namespace {

// What a generate subcommand did, reported once: a failure (`fail_code`:
// kExitUsage for unreadable input, else kExitFailed) as an error, or the
// summary (on stderr when the data went to stdout); with --json, the
// envelope instead, its own `fields` last.
void Report(Context* ctx, bool json, const std::string& input,
            const std::string& out, const Status& s, int fail_code,
            const std::string& summary,
            std::vector<std::pair<std::string, std::string>> fields) {
  std::ostream& os = out == "-" ? std::cerr : std::cout;
  const int code = s.ok() ? kExitOk : fail_code;
  RaiseExitCode(ctx, code);
  if (json) {
    JsonEnvelope e;
    e.input = input;
    e.outcome = s.ok()                    ? "ok"
                : fail_code == kExitUsage ? "input_error"
                                          : "write_failed";
    e.exit_code = code;
    e.error = s.ok() ? "" : s.message;
    e.output = s.ok() ? out : "";
    e.fields = std::move(fields);
    os << e.ToJson() << std::endl;
    return;
  }
  if (!s.ok()) {
    PrintError(s.message);
  } else if (!ctx->quiet && !summary.empty()) {
    os << summary << std::endl;
  }
}

// Writes a generated polygon to `out` (- for stdout) and reports it.
void WritePolygonOut(const PolygonData& polygon, const std::string& input,
                     const std::string& out, bool json, Context* ctx) {
  const Status s = out == "-" ? WritePolygonText(std::cout, polygon)
                              : WritePolygonText(out, polygon);
  const size_t n = polygon.vertices.size();
  // Nothing on stderr beside a polygon on stdout (as before: scripts pipe
  // both).
  Report(ctx, json, input, out, s, kExitFailed,
         out == "-" ? "" : std::to_string(n) + " vertices -> " + out,
         {{"vertices", std::to_string(n)}});
}

constexpr const char* kJsonHelp =
    "one JSON object (the envelope, then what was made) on stdout, or "
    "stderr with -o -";

}  // namespace

void AddGenerateCommand(CLI::App& app, Context* ctx) {
  CLI::App* gen = app.add_subcommand(
      "generate",
      "Write test data: the paper's curves, loop pairs, mesh holes or curve "
      "networks.");
  gen->require_subcommand(1);

  struct CurveFlags {
    std::string name;
    int n = 200;
    std::string out;
    bool json = false;
  };
  auto c = std::make_shared<CurveFlags>();
  CLI::App* curve = gen->add_subcommand(
      "curve", "monkey, mobius, spiral, moment, twist or trefoil (knotted)");
  curve->add_option("name", c->name, "curve name")->required();
  curve->add_option("-n,--vertices", c->n, "number of vertices")
      ->check(CLI::Range(3, 100000000))
      ->capture_default_str();
  curve
      ->add_option("-o,--output", c->out,
                   "polygon file to write (- for stdout)")
      ->required();
  curve->add_flag("--json", c->json, kJsonHelp);
  curve->callback([c, ctx] {
    const auto which = CurveFromName(c->name);
    if (!which) {
      Report(ctx, c->json, c->name, c->out,
             InvalidArgument("unknown curve '" + c->name + "'"), kExitUsage, "",
             {{"vertices", "0"}});
      return;
    }
    WritePolygonOut(PolygonData{MakeCurve(*which, c->n), {}}, c->name, c->out,
                    c->json, ctx);
  });

  struct LoopsFlags {
    std::string name, out;
    int n = 100;
    uint64_t seed = 1;
    bool json = false;
  };
  auto lp = std::make_shared<LoopsFlags>();
  CLI::App* loops = gen->add_subcommand(
      "loops",
      "tube or island: two loops bounding one surface, in one file (blank "
      "line between them)");
  loops->add_option("name", lp->name, "tube or island")
      ->required()
      ->check(CLI::IsMember({"tube", "island"}));
  loops->add_option("-n,--vertices", lp->n, "vertices per loop")
      ->check(CLI::Range(3, 10000000))
      ->capture_default_str();
  loops->add_option("--seed", lp->seed, "random seed")->capture_default_str();
  loops
      ->add_option("-o,--output", lp->out,
                   "polygon file to write (- for stdout)")
      ->required();
  loops->add_flag("--json", lp->json, kJsonHelp);
  loops->callback([lp, ctx] {
    WritePolygonOut(MakeLoopPair(*LoopPairFromName(lp->name), lp->n, lp->seed),
                    lp->name, lp->out, lp->json, ctx);
  });

  struct HoleFlags {
    std::string mesh, out;
    int triangles = 200;
    uint64_t seed = 1;
    bool json = false;
  };
  auto h = std::make_shared<HoleFlags>();
  CLI::App* hole = gen->add_subcommand(
      "hole",
      "Grow a disk-shaped hole on a mesh (.off/.obj) and write its boundary "
      "with the mesh's normals");
  hole->add_option("mesh", h->mesh, "triangle mesh")->required();
  hole->add_option("-t,--triangles", h->triangles, "triangles to remove")
      ->capture_default_str();
  hole->add_option("--seed", h->seed, "random seed")->capture_default_str();
  hole->add_option("-o,--output", h->out,
                   "polygon file to write (- for stdout)")
      ->required();
  hole->add_flag("--json", h->json, kJsonHelp);
  AddGenerateHolesCommand(gen, ctx);
  hole->callback([h, ctx] {
    MeshData mesh;
    Hole result;
    Status s = ReadMeshFile(h->mesh, &mesh);
    if (!s.ok()) {  // unreadable input
      Report(ctx, h->json, h->mesh, h->out, s, kExitUsage, "", {});
      return;
    }
    s = GrowHole(mesh, h->triangles, h->seed, &result);
    if (s.ok()) {
      s = h->out == "-" ? WritePolygonText(std::cout, result.boundary)
                        : WritePolygonText(h->out, result.boundary);
    }
    const size_t n = result.boundary.vertices.size();
    Report(ctx, h->json, h->mesh, h->out, s, kExitFailed,
           "hole of " + std::to_string(result.triangles) +
               " triangles, boundary of " + std::to_string(n) +
               " vertices -> " + h->out,
           {{"triangles", std::to_string(result.triangles)},
            {"vertices", std::to_string(n)}});
  });
}

void AddGenerateHolesCommand(CLI::App* gen, Context* ctx) {
  struct HolesFlags {
    std::string mesh, out, removed;
    int count = 10, triangles = 200, island = 0;
    uint64_t seed = 1;
    bool json = false;
  };
  auto h = std::make_shared<HolesFlags>();
  CLI::App* holes = gen->add_subcommand(
      "holes",
      "Cut k separate holes, grown to a size, out of a closed mesh (test data "
      "for fill-holes); the removed patches are written too (ground truth)");
  holes->add_option("mesh", h->mesh, "closed triangle mesh")->required();
  holes->add_option("-k,--count", h->count, "holes to cut")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  holes->add_option("-t,--triangles", h->triangles, "triangles per hole")
      ->check(CLI::Range(1, 100000000))
      ->capture_default_str();
  holes
      ->add_option("--island", h->island,
                   "leave an island of this many triangles floating in "
                   "each hole (0: none); the hole is the ring around it")
      ->check(CLI::Range(0, 100000000))
      ->capture_default_str();
  holes->add_option("--seed", h->seed, "random seed")->capture_default_str();
  holes->add_option("-o,--output", h->out, "the mesh with holes")->required();
  holes->add_option("--removed", h->removed,
                    "where the removed patches go (default: OUTPUT's name "
                    "with .removed before the extension)");
  holes->add_flag("--json", h->json, kJsonHelp);
  holes->callback([h, ctx] {
    MeshData mesh, holey, removed;
    Status s = ReadMeshFile(h->mesh, &mesh);
    if (!s.ok()) {
      Report(ctx, h->json, h->mesh, h->out, s, kExitUsage, "", {});
      return;
    }
    std::string removed_path = h->removed;
    if (removed_path.empty()) {
      const std::filesystem::path p(h->out);
      removed_path = (p.parent_path() /
                      (p.stem().string() + ".removed" + p.extension().string()))
                         .string();
    }
    s = CutIslandHoles(mesh, h->count, h->triangles, h->island, h->seed, &holey,
                       &removed);
    if (s.ok()) s = WriteMeshFile(h->out, holey);
    if (s.ok()) s = WriteMeshFile(removed_path, removed);
    Report(
        ctx, h->json, h->mesh, h->out, s, kExitFailed,
        std::to_string(h->count) + " holes of " + std::to_string(h->triangles) +
            " triangles" +
            (h->island > 0 ? " around islands of " + std::to_string(h->island)
                           : std::string()) +
            " -> " + h->out + " (removed patches: " + removed_path + ")",
        {{"holes", std::to_string(h->count)},
         {"removed", JsonQuote(removed_path)},
         {"faces", std::to_string(holey.triangles.size())}});
  });
  struct NetworkFlags {
    std::string source, out;
    int segments = 4, patches = 100, keep_every = 1;
    uint64_t seed = 1;
    bool json = false;
  };
  auto nf = std::make_shared<NetworkFlags>();
  CLI::App* network = gen->add_subcommand(
      "network",
      "Write a curve network (OBJ polylines) for surface: 'cube' (its 12 "
      "edges), 'cylinder' (two rims and a seam), 'lid' (the cube and a "
      "circle on its top face: an island), 'partition' (two cubes side by "
      "side: with --walls the square between them is a wall), or the rims "
      "of disk-shaped "
      "patches cut from a closed MESH file (its surface is the reference)");
  network
      ->add_option("source", nf->source,
                   "cube, cylinder, lid, partition, or a mesh file")
      ->required();
  network
      ->add_option("-s,--segments", nf->segments,
                   "cube, lid, partition: pieces per edge; cylinder: "
                   "points per rim "
                   "(lid: 6 times as many on its circle)")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  network->add_option("-p,--patches", nf->patches, "mesh: patches to cut")
      ->check(CLI::Range(2, 1000000))
      ->capture_default_str();
  network
      ->add_option("--keep-every", nf->keep_every,
                   "mesh: keep the junctions and every k-th rim vertex")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  network->add_option("--seed", nf->seed, "random seed")->capture_default_str();
  network->add_option("-o,--output", nf->out, "network .obj (- for stdout)")
      ->required();
  network->add_flag("--json", nf->json, kJsonHelp);
  network->callback([nf, ctx] {
    CurveNetwork net;
    Status s = OkStatus();
    if (nf->source == "cube") {
      net = CubeNetwork(nf->segments);
    } else if (nf->source == "cylinder") {
      net = CylinderNetwork(std::max(3, nf->segments), /*seam=*/true);
    } else if (nf->source == "lid") {
      net = LidNetwork(nf->segments, 6 * nf->segments);
    } else if (nf->source == "partition") {
      net = PartitionNetwork(nf->segments);
    } else {
      MeshData mesh;
      s = ReadMeshFile(nf->source, &mesh);
      if (!s.ok()) {  // unreadable input
        Report(ctx, nf->json, nf->source, nf->out, s, kExitUsage, "", {});
        return;
      }
      CutNetwork cut;
      if (s.ok()) {
        s = CutIntoPatches(mesh, nf->patches, nf->keep_every, nf->seed, &cut);
      }
      net = std::move(cut.network);
    }
    if (s.ok()) {
      if (nf->out == "-") {
        s = WriteNetworkObj(std::cout, net);
      } else {
        std::ofstream out(nf->out);
        s = out ? WriteNetworkObj(out, net)
                : InvalidArgument("cannot write '" + nf->out + "'");
      }
    }
    Report(ctx, nf->json, nf->source, nf->out, s, kExitFailed,
           std::to_string(net.polylines.size()) + " polylines, " +
               std::to_string(net.vertices.size()) + " vertices -> " + nf->out,
           {{"polylines", std::to_string(net.polylines.size())},
            {"vertices", std::to_string(net.vertices.size())}});
  });
}

}  // namespace dot::client
