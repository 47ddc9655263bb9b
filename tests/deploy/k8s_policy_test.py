#!/usr/bin/python3
# SPDX-License-Identifier: AGPL-3.0-or-later
"""Policy checks of the deployment files, as rendered for a cluster.

Renders deploy/k8s and deploy/prometheus-operator with `kubectl kustomize`
and checks what operators rely on: the HorizontalPodAutoscaler owns the
scale (no replicas beside it), images by version (never latest), every
container with requests, limits and both probes, metrics scraped per pod
(annotations naming a declared port, no Service exposing it, a PodMonitor
in the operator overlay), and the image's metrics bound where EXPOSE says,
with OCI labels. Exit 77 (skipped) without kubectl 1.21 or later.
"""
import json
import pathlib
import re
import shutil
import subprocess
import sys

import yaml

ROOT = pathlib.Path(__file__).resolve().parents[2]
failures = []


def check(ok, what):
    if not ok:
        failures.append(what)


def render(directory):
    out = subprocess.run(["kubectl", "kustomize", str(ROOT / directory)],
                         check=True, capture_output=True, text=True).stdout
    return [d for d in yaml.safe_load_all(out) if d]


def main():
    if shutil.which("kubectl") is None:
        print("kubectl not installed: skipped")
        return 77
    # Debian bookworm's kubernetes-client (1.20) embeds kustomize 2, which
    # reads neither `labels:` nor a directory as a resource.
    version = json.loads(subprocess.run(
        ["kubectl", "version", "--client", "-o", "json"], check=True,
        capture_output=True, text=True).stdout)["clientVersion"]
    minor = int("".join(c for c in version["minor"] if c.isdigit()) or 0)
    if (int(version["major"]), minor) < (1, 21):
        print(f"kubectl {version['gitVersion']} is older than 1.21 "
              "(kustomize 4): skipped")
        return 77
    base = render("deploy/k8s")
    overlay = render("deploy/prometheus-operator")
    by_kind = {}
    for d in base:
        by_kind.setdefault(d["kind"], []).append(d)
    deployments = {d["metadata"]["name"]: d for d in by_kind["Deployment"]}
    for hpa in by_kind.get("HorizontalPodAutoscaler", []):
        target = deployments.get(hpa["spec"]["scaleTargetRef"]["name"])
        check(target is not None, "the HPA targets no Deployment of the base")
        if target is not None:
            check("replicas" not in target["spec"],
                  "spec.replicas beside the HPA resets its scale on apply")
    metrics_ports = set()
    for name, d in deployments.items():
        pod = d["spec"]["template"]
        for c in pod["spec"]["containers"]:
            image = c["image"]
            tag = image.rsplit(":", 1)[1] if ":" in image.split("/")[-1] else ""
            check("@sha256:" in image or (tag and tag != "latest"),
                  f"{name}: image {image!r} is not pinned to a version")
            res = c.get("resources", {})
            check("requests" in res and "limits" in res,
                  f"{name}/{c['name']}: requests and limits")
            check("readinessProbe" in c and "livenessProbe" in c,
                  f"{name}/{c['name']}: readiness and liveness probes")
            ports = {p.get("name"): p["containerPort"] for p in c.get("ports", [])}
            if "metrics" in ports:
                metrics_ports.add(ports["metrics"])
        notes = pod["metadata"].get("annotations", {})
        check(notes.get("prometheus.io/scrape") == "true",
              f"{name}: pods not annotated for scraping")
        check(int(notes.get("prometheus.io/port", 0)) in metrics_ports,
              f"{name}: the scrape port is no declared metrics port")
        check(notes.get("prometheus.io/path") == "/metrics",
              f"{name}: the scrape path")
    for svc in by_kind.get("Service", []):
        for p in svc["spec"]["ports"]:
            check(p.get("targetPort") != "metrics" and
                  p.get("port") not in metrics_ports,
                  f"Service {svc['metadata']['name']} exposes metrics: each "
                  "scrape would reach a random pod")
    monitors = [d for d in overlay if d["kind"] == "PodMonitor"]
    check(len(monitors) == 1, "the operator overlay has one PodMonitor")
    pod_labels = next(iter(deployments.values()))["spec"]["template"][
        "metadata"]["labels"]
    for m in monitors:
        wanted = m["spec"]["selector"]["matchLabels"]
        check(all(pod_labels.get(k) == v for k, v in wanted.items()),
              "the PodMonitor selects no dot-server pod")
        check([e["port"] for e in m["spec"]["podMetricsEndpoints"]] ==
              ["metrics"], "the PodMonitor scrapes the port named metrics")
    check(len(overlay) == len(base) + len(monitors),
          "the operator overlay is the base plus the PodMonitor")
    # The image: metrics on every interface, as EXPOSE says, and OCI labels.
    docker = (ROOT / "Dockerfile").read_text()
    final = docker[docker.rindex("\nFROM "):]
    exposed = set(re.findall(r"\d+", re.search(r"^EXPOSE (.*)$", final, re.M)[1]))
    port = re.search(r"DOT_METRICS_PORT=(\d+)", final)[1]
    check(port in exposed, "the metrics port is not EXPOSEd")
    check("DOT_METRICS_BIND=0.0.0.0" in final,
          "the image binds metrics to loopback while EXPOSE publishes them")
    for label in ("title", "description", "version", "revision", "licenses"):
        check(f"org.opencontainers.image.{label}=" in final,
              f"the image has no OCI label {label}")
    for f in failures:
        print("FAIL:", f)
    print(f"{len(base)} base resources, {len(overlay)} with the operator "
          f"overlay: {len(failures)} policy failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
