#!/usr/bin/env bash
# What a snapshot costs the TypeScript client (client/web/client, docs/WEB.md) to
# receive, in node: decoding, applying (the predictor over every body held), the view
# hash, and the whole path through Client, for 1,000 and 4,000 bodies held and 10 or
# 100 records a snapshot, with and without a view hash; CPU microseconds per
# snapshot, the median of REPEATS runs (default 5). Builds the package first
# (npm ci and npm run build, as scripts/test-web.sh does) when its dist/ is missing.
# Writes bench/results/web-client.csv (OUT=FILE writes there instead).
set -euo pipefail
cd "$(dirname "$0")/.."
out="${OUT:-bench/results/web-client.csv}"
package=client/web/client
if [ ! -f "$package/dist/index.js" ]; then
  (cd "$package" && npm ci --no-audit --no-fund --loglevel=error && npm run --silent build)
fi
echo "web-client: node $(node --version)" >&2
(cd "$package" && node bench/receive.mjs) >"$out.tmp"
mv "$out.tmp" "$out"
cat "$out"
