// Example: the viewer started from JavaScript with startViewer, fed a clip from parseMotion.
import init, { parseMotion, startViewer } from '../../pkg/mocap_web.js';

await init();
const viewer = await startViewer(document.getElementById('viewer'), { embed: true });
window.exampleViewer = viewer;
const response = await fetch('../../data/walk.bvh');
const clip = parseMotion(new Uint8Array(await response.arrayBuffer()), 'walk.bvh');
viewer.loadClip(clip, 'walk.bvh');
clip.free();
document.getElementById('play').addEventListener('click', () => viewer.play());
document.getElementById('pause').addEventListener('click', () => viewer.pause());
document.getElementById('first').addEventListener('click', () => viewer.seek(0));
