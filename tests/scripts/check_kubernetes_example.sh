#!/usr/bin/env bash
# examples/kubernetes/ holds YAML that Kubernetes accepts in form (an Indexed Job of N
# completions, a merge Job, one claim mounted by both, N the same everywhere) and commands that
# prt accepts: each pod's shell script is taken from the manifest, expanded as Kubernetes expands
# $(VAR) and $$ in args, and run here with the pod's environment (the volume's mount path mapped
# to a scratch folder, JOB_COMPLETION_INDEX = 0..N-1 as the Job controller sets it, prt on the
# PATH as in the image), then the merge pod's script; the merged file must equal, byte for byte,
# one `prt bake` of the same scene with the manifest's PRT_BAKE_OPTIONS. The scene is a small
# level (1,416 vertices) under the manifest's own options: a few seconds.
# Skips (77) without python3's yaml module.
# Usage: check_kubernetes_example.sh PRT_BINARY SOURCE_DIR
set -euo pipefail
prt="$(realpath "$1")"
source_dir="$(realpath "$2")"
python3 -c 'import yaml' 2>/dev/null || { echo "SKIP: python3 has no yaml module"; exit 77; }
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT

# Form checks, and per Job: the expanded script and its environment (NAME=VALUE lines, the
# mount path replaced by the scratch folder).
python3 - "$source_dir/examples/kubernetes" "$scratch" <<'PY'
import os, re, sys, yaml

src, scratch = sys.argv[1], sys.argv[2]
farm = os.path.join(scratch, "farm")
def fail(msg):
    print("FAIL: " + msg)
    sys.exit(1)

def load(name):
    with open(os.path.join(src, name)) as f:
        return list(yaml.safe_load_all(f))

def expand(text, env):
    # Kubernetes' expansion of command and args: $$ is $, $(NAME) is NAME's value when the
    # container defines NAME, anything else is left as written.
    def one(m):
        if m.group(0) == "$$":
            return "$"
        return env.get(m.group(1), m.group(0))
    return re.sub(r"\$\$|\$\(([A-Za-z_][A-Za-z0-9_]*)\)", one, text)

bake_docs, merge_docs = load("bake-job.yaml"), load("merge-job.yaml")
claims = [d for d in bake_docs if d["kind"] == "PersistentVolumeClaim"]
jobs = {d["metadata"]["name"]: d for d in bake_docs + merge_docs if d["kind"] == "Job"}
if len(claims) != 1 or "ReadWriteMany" not in claims[0]["spec"]["accessModes"]:
    fail("bake-job.yaml: one ReadWriteMany PersistentVolumeClaim expected")
if set(jobs) != {"prt-bake", "prt-merge"}:
    fail("expected the Jobs prt-bake and prt-merge, found %s" % sorted(jobs))
bake = jobs["prt-bake"]["spec"]
if bake.get("completionMode") != "Indexed":
    fail("prt-bake: completionMode is not Indexed")

shards = None
for name, job in jobs.items():
    if job["apiVersion"] != "batch/v1":
        fail(name + ": apiVersion is not batch/v1")
    pod = job["spec"]["template"]["spec"]
    if pod.get("restartPolicy") not in ("Never", "OnFailure"):
        fail(name + ": a Job's pods need restartPolicy Never or OnFailure")
    (container,) = pod["containers"]
    env = {e["name"]: str(e["value"]) for e in container["env"]}
    if shards is None:
        shards = env["PRT_SHARDS"]
    if env["PRT_SHARDS"] != shards:
        fail(name + ": PRT_SHARDS %s differs from prt-bake's %s" % (env["PRT_SHARDS"], shards))
    (volume,) = pod["volumes"]
    if volume["persistentVolumeClaim"]["claimName"] != claims[0]["metadata"]["name"]:
        fail(name + ": does not mount the claim " + claims[0]["metadata"]["name"])
    (mount,) = [m for m in container["volumeMounts"] if m["name"] == volume["name"]]
    if container["command"] != ["/bin/sh", "-c"] or len(container["args"]) != 1:
        fail(name + ": expected command [/bin/sh, -c] and one script in args")
    script = expand(container["args"][0], env)
    with open(os.path.join(scratch, name + ".sh"), "w") as f:
        f.write(script)
    with open(os.path.join(scratch, name + ".env"), "w") as f:
        for key, value in env.items():
            f.write("%s=%s\n" % (key, value.replace(mount["mountPath"], farm)))
if str(bake["completions"]) != shards:
    fail("prt-bake: completions %s but PRT_SHARDS %s" % (bake["completions"], shards))
if "--shard \"auto/$PRT_SHARDS\"" not in jobs["prt-bake"]["spec"]["template"]["spec"]["containers"][0]["args"][0]:
    fail("prt-bake: the script does not bake --shard auto/$PRT_SHARDS")
with open(os.path.join(scratch, "shards"), "w") as f:
    f.write(shards)
print("ok: manifests (Indexed Job of %s completions, merge Job, one claim)" % shards)
PY

shards="$(cat "$scratch/shards")"
mkdir -p "$scratch/farm" "$scratch/bin"
ln -s "$prt" "$scratch/bin/prt"
# The scene the manifest names, at its path on the volume.
scene="$(sed -n 's/^PRT_SCENE=//p' "$scratch/prt-bake.env")"
"$prt" make-scene --scene level --rooms 2 --objects 30 --triangles 1200 -o "$scene" >/dev/null
pod() {  # job [JOB_COMPLETION_INDEX]
  local vars=()
  mapfile -t vars <"$scratch/$1.env"
  [[ $# -ge 2 ]] && vars+=("JOB_COMPLETION_INDEX=$2")
  (cd "$scratch" && env -i PATH="$scratch/bin:/usr/bin:/bin" PRT_PROGRESS_INTERVAL=60 \
    "${vars[@]}" /bin/sh "$scratch/$1.sh") >"$scratch/$1.log" 2>&1 ||
    { echo "FAIL: the $1 pod's script exited with status $? (${2:+index $2}):"; cat "$scratch/$1.log"; exit 1; }
}
for ((i = 0; i < shards; i++)); do pod prt-bake "$i"; done
pod prt-merge
output="$(sed -n 's/^PRT_OUTPUT=//p' "$scratch/prt-merge.env")"
options="$(sed -n 's/^PRT_BAKE_OPTIONS=//p' "$scratch/prt-bake.env")"
# shellcheck disable=SC2086  # a list of options
"$prt" bake "$scene" $options --quiet -o "$scratch/single.prt"
if cmp -s "$output" "$scratch/single.prt"; then
  echo "ok: $shards pods and the merge give the bytes of one prt bake ($(stat -c %s "$output") bytes)"
else
  echo "FAIL: the merged $output differs from one prt bake $options"
  exit 1
fi
