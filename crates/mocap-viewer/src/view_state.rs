//! The view state as a URL fragment (`t=3.25&speed=0.5&cam=…&sel=LeftHand`): written
//! from a [`Viewer`] and read back exactly (numbers use Rust's shortest round-trip
//! formatting, so `parse(format(x)) == x` bit for bit).
//!
//! Keys: `t` seconds (or `f` frame), `play` 0/1, `speed`, `loop` 0/1, `range` `a-b`
//! (frames of the timeline, `all` for the whole of it), `cam` `yaw,pitch,distance,x,y,z`
//! (radians, then metres: every clip is scaled to metres by its guessed unit),
//! `sel` a joint name, of the first character (`sel=LeftHand`) or of character `n`,
//! 1-based (`sel=2:LeftHand`; a colon inside a name is written `%3A`), `layout`
//! `spread` or `overlay`, `hide` a comma list of hidden characters' numbers (1-based
//! like `sel`; `none` or absent when all are shown), `offset` the hand-set offsets in
//! metres as `n:x,y,z` joined by `;` (`offset=2:0.5,0,-1`; characters not listed sit
//! at zero; `none` or absent when all are zero), `mode` `capsules`, `sticks` or `body`,
//! `anim` the animations models play as `n:name` joined by `;` (`anim=1:run`; models
//! not listed play all their frames; `none` or absent when all do), `up` the file
//! axis that points up in each character, one letter per character in order (`up=yz`:
//! the second is Z-up; absent: as guessed when the clips opened),
//! `shadows` 0/1, `quality` `auto`, `full` or `fast` (see [`crate::quality`]), `draw` a comma list of `joints`, `axes`, `follow`, `interp`, `weights`, `pose`, `footlock`, `cubic`, `onion`, `trails`, `onion` the onion skin's poses each side and seconds apart
//! (`onion=3,0.2`, written while it is on), and `panels` a comma list of `tree`, `inspector` (or
//! `none`). Timeline frames (`f`, `range`, the frame shown) count in the frame time
//! of the selection's character, else the first one. Unknown keys and unreadable
//! values are ignored; missing keys leave the viewer as it is.

use crate::layout::Layout;
use crate::state::AppState;
use mocap::glam::Vec3;

/// A parsed fragment: every field is optional (absent = leave as is).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ViewState {
    /// Playhead in seconds.
    pub time: Option<f64>,
    /// Playhead as a frame (used when `time` is absent).
    pub frame: Option<usize>,
    /// Playing or paused.
    pub playing: Option<bool>,
    /// Playback speed factor.
    pub speed: Option<f32>,
    /// Loop at the end.
    pub looping: Option<bool>,
    /// Loop sub-range: `Some(None)` is the whole clip.
    pub range: Option<Option<(usize, usize)>>,
    /// Camera: yaw, pitch, distance, target.
    pub camera: Option<(f32, f32, f32, Vec3)>,
    /// Selected character (0-based) and joint name (`Some(None)`: no selection).
    pub selected: Option<Option<(usize, String)>>,
    /// Spread or overlay.
    pub layout: Option<Layout>,
    /// Hidden characters (0-based; written 1-based); `Some(empty)` shows all.
    pub hidden: Option<Vec<usize>>,
    /// Hand-set offsets in metres by character (0-based; written 1-based); the rest are zero.
    pub offsets: Option<Vec<(usize, Vec3)>>,
    /// Animations played by models (0-based character; written 1-based); the rest play all frames.
    pub animations: Option<Vec<(usize, String)>>,
    /// The up axis of each character, in order (models take none).
    pub up: Option<Vec<mocap::UpAxis>>,
    /// Capsules, sticks or body.
    pub mode: Option<crate::settings::DrawMode>,
    /// Soft shadows on the floor.
    pub shadows: Option<bool>,
    /// The 3D view's quality.
    pub quality: Option<crate::quality::Quality>,
    /// Draw flags: joints, axes, follow root, interpolate, weights view, pose mode.
    pub draw: Option<[bool; 10]>,
    /// Onion skin: poses each side (1 to 8) and seconds apart (0.02 to 2).
    pub onion: Option<(usize, f64)>,
    /// Panels: hierarchy, inspector.
    pub panels: Option<[bool; 2]>,
}

const DRAW_NAMES: [&str; 10] =
    ["joints", "axes", "follow", "interp", "weights", "pose", "footlock", "cubic", "onion", "trails"];
const PANEL_NAMES: [&str; 2] = ["tree", "inspector"];

impl ViewState {
    /// Reads a fragment (with or without the leading `#`).
    pub fn parse(fragment: &str) -> ViewState {
        let mut s = ViewState::default();
        for pair in fragment.trim_start_matches('#').split('&') {
            let (key, raw) = pair.split_once('=').unwrap_or((pair, ""));
            if key == "sel" {
                s.selected = Some(parse_selection(raw));
                continue;
            }
            if key == "anim" {
                s.animations = parse_animations(raw);
                continue;
            }
            let value = percent_decode(raw);
            let v = value.as_str();
            match key {
                "t" => s.time = v.parse().ok().filter(|t: &f64| t.is_finite() && *t >= 0.0),
                "f" => s.frame = v.parse().ok(),
                "play" => s.playing = flag(v),
                "speed" => s.speed = v.parse().ok().filter(|x: &f32| x.is_finite() && *x > 0.0),
                "loop" => s.looping = flag(v),
                "range" => s.range = parse_range(v),
                "cam" => s.camera = parse_camera(v),
                "layout" => s.layout = Layout::parse(v),
                "hide" => s.hidden = parse_hidden(v),
                "offset" => s.offsets = parse_offsets(v),
                "up" => s.up = parse_up(v),
                "draw" => s.draw = Some(flags(v, DRAW_NAMES)),
                "mode" => s.mode = crate::settings::DrawMode::from_name(v),
                "shadows" => s.shadows = flag(v),
                "quality" => s.quality = crate::quality::Quality::from_name(v),
                "panels" => s.panels = Some(flags(v, PANEL_NAMES)),
                "onion" => s.onion = parse_onion(v),
                _ => {}
            }
        }
        s
    }

    /// Everything the viewer shows, as a fragment (no leading `#`).
    pub fn format(viewer: &AppState) -> String {
        let p = &viewer.playback;
        let c = &viewer.camera;
        let st = &viewer.settings;
        let mut parts = vec![
            format!("t={}", p.time),
            format!("play={}", u8::from(p.playing)),
            format!("speed={}", p.speed),
            format!("loop={}", u8::from(p.looping)),
        ];
        if let Some((a, b)) = p.range {
            parts.push(format!("range={a}-{b}"));
        }
        parts.push(format!("cam={},{},{},{},{},{}", c.yaw, c.pitch, c.distance, c.target.x, c.target.y, c.target.z));
        if let (Some(sel), Some(name)) = (viewer.selected, viewer.selected_name()) {
            let name = percent_encode(name);
            let number = sel.character + 1;
            parts.push(if number == 1 { format!("sel={name}") } else { format!("sel={number}:{name}") });
        }
        parts.push(format!("layout={}", viewer.stage.layout.name()));
        let hidden: Vec<String> = viewer
            .stage
            .actors
            .iter()
            .enumerate()
            .filter(|(_, c)| !c.visible)
            .map(|(i, _)| (i + 1).to_string())
            .collect();
        if !hidden.is_empty() {
            parts.push(format!("hide={}", hidden.join(",")));
        }
        let moved: Vec<String> = (viewer.stage.actors.iter().enumerate())
            .filter(|(_, c)| c.offset != Vec3::ZERO)
            .map(|(i, c)| format!("{}:{},{},{}", i + 1, c.offset.x, c.offset.y, c.offset.z))
            .collect();
        if !moved.is_empty() {
            parts.push(format!("offset={}", moved.join(";")));
        }
        let animations: Vec<String> = (viewer.stage.actors.iter().enumerate())
            .filter_map(|(i, c)| match (c.model(), c.clip()) {
                (Some(m), _) => m.animation().map(|_| (i, m.animation_name())),
                // A character's take, when it is not the file's first.
                (None, Some(clip)) => {
                    clip.take_name().filter(|n| clip.takes().first().is_some_and(|t| t.name != *n)).map(|n| (i, n))
                }
                _ => None,
            })
            .map(|(i, name)| format!("{}:{}", i + 1, percent_encode(name)))
            .collect();
        if !animations.is_empty() {
            parts.push(format!("anim={}", animations.join(";")));
        }
        if !viewer.stage.actors.is_empty() {
            parts.push(format!("up={}", viewer.stage.actors.iter().map(|c| c.up.name()).collect::<String>()));
        }
        parts.push(format!("mode={}", st.mode.name()));
        parts.push(format!("shadows={}", u8::from(st.shadows)));
        parts.push(format!("quality={}", st.quality.name()));
        let draw = [
            st.show_joints,
            st.show_axes,
            st.follow_root,
            st.between != mocap::Interpolation::Nearest,
            st.show_weights,
            st.pose_mode,
            st.foot_lock,
            st.between == mocap::Interpolation::Cubic,
            st.onion,
            st.trails,
        ];
        parts.push(format!("draw={}", join_flags(draw, DRAW_NAMES)));
        if st.onion {
            parts.push(format!("onion={},{}", st.onion_count, st.onion_step));
        }
        let panels = [viewer.panels.hierarchy, viewer.panels.inspector];
        parts.push(format!("panels={}", join_flags(panels, PANEL_NAMES)));
        parts.join("&")
    }
}

/// `N,STEP`: the onion skin's poses each side and seconds apart, each in the
/// View menu's range.
fn parse_onion(v: &str) -> Option<(usize, f64)> {
    let (count, step) = v.split_once(',')?;
    let count: usize = count.trim().parse().ok().filter(|n| (1..=8).contains(n))?;
    let step: f64 = step.trim().parse().ok().filter(|s: &f64| (0.02..=2.0).contains(s))?;
    Some((count, step))
}

fn flag(v: &str) -> Option<bool> {
    match v {
        "1" | "true" => Some(true),
        "0" | "false" => Some(false),
        _ => None,
    }
}

fn flags<const N: usize>(v: &str, names: [&str; N]) -> [bool; N] {
    let items: Vec<&str> = v.split(',').collect();
    names.map(|n| items.contains(&n))
}

fn join_flags<const N: usize>(on: [bool; N], names: [&str; N]) -> String {
    let list: Vec<&str> = names.iter().zip(on).filter(|(_, on)| *on).map(|(n, _)| *n).collect();
    if list.is_empty() { "none".to_owned() } else { list.join(",") }
}

/// `Name` (character 1) or `n:Name` (character `n`, 1-based), from the raw (still
/// percent-encoded) value, so an encoded colon inside a name is not a separator.
fn parse_selection(raw: &str) -> Option<(usize, String)> {
    if raw.is_empty() {
        return None;
    }
    let (character, name) = split_numbered(raw).unwrap_or((0, raw));
    Some((character, percent_decode(name)))
}

/// `n:rest` with `n` a 1-based number: `(n - 1, rest)`.
pub(crate) fn split_numbered(s: &str) -> Option<(usize, &str)> {
    let (n, rest) = s.split_once(':')?;
    Some((n.parse::<usize>().ok()?.checked_sub(1)?, rest))
}

/// `none`, empty, or a comma list of 1-based character numbers (0-based out).
fn parse_hidden(v: &str) -> Option<Vec<usize>> {
    if v.is_empty() || v == "none" {
        return Some(Vec::new());
    }
    v.split(',').map(|n| n.trim().parse::<usize>().ok()?.checked_sub(1)).collect()
}

/// `none`, empty, or `n:name` items joined by `;` (`n` 1-based, 0-based out; the
/// name percent-encoded), from the raw value.
/// `up=yzy`: one axis letter per character; `None` when a letter is neither.
fn parse_up(v: &str) -> Option<Vec<mocap::UpAxis>> {
    v.chars().map(|c| mocap::UpAxis::from_name(c.encode_utf8(&mut [0; 4]))).collect()
}

fn parse_animations(raw: &str) -> Option<Vec<(usize, String)>> {
    if raw.is_empty() || raw == "none" {
        return Some(Vec::new());
    }
    raw.split(';').map(|item| split_numbered(item).map(|(n, name)| (n, percent_decode(name)))).collect()
}

/// `none`, empty, or `n:x,y,z` items joined by `;` (`n` 1-based, 0-based out; finite numbers).
fn parse_offsets(v: &str) -> Option<Vec<(usize, Vec3)>> {
    if v.is_empty() || v == "none" {
        return Some(Vec::new());
    }
    let item = |s: &str| {
        let (n, xyz) = split_numbered(s)?;
        let n3: Vec<f32> = xyz.split(',').map(str::parse).collect::<Result<_, _>>().ok()?;
        match n3.as_slice() {
            &[x, y, z] if n3.iter().all(|x| x.is_finite()) => Some((n, Vec3::new(x, y, z))),
            _ => None,
        }
    };
    v.split(';').map(item).collect()
}

fn parse_range(v: &str) -> Option<Option<(usize, usize)>> {
    if v == "all" {
        return Some(None);
    }
    let (a, b) = v.split_once('-')?;
    Some(Some((a.parse().ok()?, b.parse().ok()?)))
}

fn parse_camera(v: &str) -> Option<(f32, f32, f32, Vec3)> {
    let n: Vec<f32> = v.split(',').map(str::parse).collect::<Result<_, _>>().ok()?;
    match n.as_slice() {
        &[yaw, pitch, distance, x, y, z] if n.iter().all(|x| x.is_finite()) && distance > 0.0 => {
            Some((yaw, pitch, distance, Vec3::new(x, y, z)))
        }
        _ => None,
    }
}

/// Percent-encodes everything but unreserved characters (UTF-8 bytes).
pub fn percent_encode(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for b in s.bytes() {
        if b.is_ascii_alphanumeric() || matches!(b, b'-' | b'.' | b'_' | b'~') {
            out.push(char::from(b));
        } else {
            out.push_str(&format!("%{b:02X}"));
        }
    }
    out
}

/// Decodes `%XX` escapes (invalid escapes stay as written; invalid UTF-8 is replaced).
pub fn percent_decode(s: &str) -> String {
    let bytes = s.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while let Some(&b) = bytes.get(i) {
        let hex = |k: usize| bytes.get(k).and_then(|c| char::from(*c).to_digit(16));
        match (b, hex(i + 1), hex(i + 2)) {
            (b'%', Some(hi), Some(lo)) => {
                out.push((hi * 16 + lo) as u8);
                i += 3;
            }
            _ => {
                out.push(b);
                i += 1;
            }
        }
    }
    String::from_utf8_lossy(&out).into_owned()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn percent_round_trip() {
        for s in ["LeftHand", "left hand:1", "Ünïcode&=#%", ""] {
            assert_eq!(percent_decode(&percent_encode(s)), s);
        }
        assert_eq!(percent_decode("%zz%4"), "%zz%4");
    }

    #[test]
    fn draw_mode_and_shadows() {
        let s = ViewState::parse("mode=sticks&shadows=0");
        assert_eq!((s.mode, s.shadows), (Some(crate::settings::DrawMode::Sticks), Some(false)));
        let s = ViewState::parse("mode=boxes&shadows=maybe");
        assert_eq!((s.mode, s.shadows), (None, None));
        assert_eq!(ViewState::parse("quality=fast").quality, Some(crate::quality::Quality::Fast));
        assert_eq!(ViewState::parse("quality=ultra").quality, None);
    }

    #[test]
    fn up_axes_by_character() {
        assert_eq!(ViewState::parse("up=yz").up, Some(vec![mocap::UpAxis::Y, mocap::UpAxis::Z]));
        assert_eq!(ViewState::parse("up=Z").up, Some(vec![mocap::UpAxis::Z]));
        assert_eq!(ViewState::parse("up=yx").up, None, "an unknown letter: nothing");
        assert_eq!(ViewState::parse("t=1").up, None);
    }

    #[test]
    fn animations_by_character() {
        let s = ViewState::parse("anim=1:run;3:pain%31");
        assert_eq!(s.animations, Some(vec![(0, "run".to_owned()), (2, "pain1".to_owned())]));
        assert_eq!(ViewState::parse("anim=none").animations, Some(Vec::new()));
        assert_eq!(ViewState::parse("anim=x:run").animations, None);
    }

    #[test]
    fn parse_ignores_junk() {
        let s = ViewState::parse("#t=abc&speed=-1&cam=1,2&range=x&nothing&play=1&draw=axes,bogus");
        assert_eq!(s.time, None);
        assert_eq!(s.speed, None);
        assert_eq!(s.camera, None);
        assert_eq!(s.range, None);
        assert_eq!(s.playing, Some(true));
        assert_eq!(s.draw, Some([false, true, false, false, false, false, false, false, false, false]));
    }
}
