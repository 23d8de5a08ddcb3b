// The Node.js the project needs (package.json's engines): `npm test`, the benches
// and CI stop at once with a clear message on an older one, instead of failing
// later on syntax or APIs it lacks. Debian 12's own nodejs is 18.
const REQUIRED = [20, 19];

export function requireNode() {
  const [major, minor] = process.versions.node.split('.').map(Number);
  if (major > REQUIRED[0] || (major === REQUIRED[0] && minor >= REQUIRED[1])) return;
  console.error(
    `This project needs Node.js ${REQUIRED.join('.')} or newer; this is ${process.versions.node}.\n` +
      'Install a current Node.js (https://nodejs.org, or nvm), then run the command again.',
  );
  process.exit(1);
}

// `node scripts/require-node.mjs` checks from a shell script (.ci/run).
if (import.meta.url === `file://${process.argv[1]}`) requireNode();
