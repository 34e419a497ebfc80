// web/passes/index.js — the extra render passes of the viewer (docs/VIEWER.md, "Adding a pass").
// Each pass is a module in this folder exporting a default object
//   { name, label, init(context), render(context) }
// and listed below; the viewer adds `label` to the display switch and, while it is chosen,
// calls render(context) instead of its own draw (context: viewer.js makePassContext()).
import { ssaoPass, gtaoPass } from './ao_passes.js';

export const passes = [ssaoPass, gtaoPass];
