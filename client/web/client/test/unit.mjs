// `npm run test:unit`: the tests that need no server, no link conditioner and no
// browser, i.e. every test/*.test.mjs that does not start processes through
// ./server.mjs. scripts/test.sh --quick runs these; `npm test` runs them all.
import { readdirSync, readFileSync } from "node:fs";
import { spawnSync } from "node:child_process";
import { fileURLToPath } from "node:url";

const dir = fileURLToPath(new URL(".", import.meta.url));
const files = readdirSync(dir)
  .filter((name) => name.endsWith(".test.mjs"))
  .filter((name) => !/from "\.\/server\.mjs"/.test(readFileSync(`${dir}${name}`, "utf8")))
  .sort()
  .map((name) => `${dir}${name}`);
const result = spawnSync(process.execPath, ["--test", ...files], { stdio: "inherit" });
process.exit(result.status ?? 1);
