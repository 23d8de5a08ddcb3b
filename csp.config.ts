/**
 * The workbench's Content-Security-Policy (docs/security.md says why each part is
 * there). The production build carries it in a <meta> tag, and `vite preview`
 * sends it as a header too (with frame-ancestors, which only a header can carry).
 * The dev server does not set it: Vite's dev client injects inline scripts and
 * styles for hot reload.
 */
export const CONTENT_SECURITY_POLICY: Record<string, string[]> = {
  'default-src': ["'self'"],
  // No inline script, no eval; WebAssembly compilation only (the simulator runs the firmware as wasm).
  'script-src': ["'self'", "'wasm-unsafe-eval'"],
  'worker-src': ["'self'"],
  'style-src': ["'self'"],
  // data: for the favicon, blob: for images the page makes (exports, previews).
  'img-src': ["'self'", 'data:', 'blob:'],
  'connect-src': ["'self'"],
  'font-src': ["'self'"],
  'object-src': ["'none'"],
  'base-uri': ["'self'"],
  'form-action': ["'none'"],
};

/** Directives a <meta> tag cannot carry (the browser ignores them there, with a warning). */
const HEADER_ONLY: Record<string, string[]> = { 'frame-ancestors': ["'none'"] };

function serialize(policy: Record<string, string[]>): string {
  return Object.entries(policy)
    .map(([directive, sources]) => `${directive} ${sources.join(' ')}`)
    .join('; ');
}

export const CSP_META = serialize(CONTENT_SECURITY_POLICY);
export const CSP_HEADER = serialize({ ...CONTENT_SECURITY_POLICY, ...HEADER_ONLY });
