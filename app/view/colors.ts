/** The view's palette: segment states (the paper's Figure 3) and the scene. */
export const STATE_COLORS = {
  unplanned: '#b8c2cc',
  planned: '#2f6fde',
  transmitted: '#e69a1c',
  historical: '#56606b',
} as const;

export const SCENE_COLORS = {
  background: '#f7f8fa',
  grid: '#dde2e8',
  gridCenter: '#c3cad3',
  tool: '#d64045',
  origin: '#2a9d8f',
} as const;
