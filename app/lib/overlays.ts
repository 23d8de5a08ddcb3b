/**
 * Menus and dialogs that are open, so that Esc can close them. Esc is STOP
 * everywhere (users of machine UIs expect it): with a menu open it closes the
 * menu AND stops the machine, and the log says both.
 */
const open = new Map<string, () => void>();

/** Registers an open overlay under its name (what the log calls it); returns the unregister. */
export function overlayOpened(name: string, close: () => void): () => void {
  open.set(name, close);
  return () => {
    if (open.get(name) === close) open.delete(name);
  };
}

/** Closes every open overlay; returns their names. */
export function closeOverlays(): string[] {
  const names = [...open.keys()];
  const closers = [...open.values()];
  open.clear();
  for (const close of closers) close();
  return names;
}
