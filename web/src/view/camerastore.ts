// The camera as the user left it, kept across reloads like the model: the rig's state
// (view/camera.ts `CameraState`) in localStorage under 'softsculpt.camera', written each time the
// view settles and read when the page frames its first model. Storage refused (private mode):
// nothing is kept, and the page frames the model anew.

import type { CameraRig } from './camera';

const CAMERA_KEY = 'softsculpt.camera';

/** Put the camera where it was left; false if nothing (well-formed) was kept. */
export function restoreCamera(rig: CameraRig): boolean {
  try {
    const s = JSON.parse(localStorage.getItem(CAMERA_KEY) ?? 'null');
    if (!s || !Array.isArray(s.position) || !Array.isArray(s.target)) return false;
    rig.restore(s);
    return true;
  } catch { return false; }
}

/** Keep the camera where it is now. */
export function saveCamera(rig: CameraRig): void {
  try { localStorage.setItem(CAMERA_KEY, JSON.stringify(rig.state())); } catch { /* private mode: not kept */ }
}
