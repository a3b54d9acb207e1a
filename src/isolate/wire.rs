//! The bytes between the parent and the isolated child (`isolate`): the request (mesher,
//! parameters, input) and the answer (the run, or the error), each written and read back
//! bit for bit; the grammar is in `isolate`'s module docs.

use super::*;
pub(super) fn put_u32(b: &mut Vec<u8>, v: u32) {
    b.extend_from_slice(&v.to_le_bytes());
}

pub(super) fn put_u64(b: &mut Vec<u8>, v: u64) {
    b.extend_from_slice(&v.to_le_bytes());
}

pub(super) fn put_f64(b: &mut Vec<u8>, v: f64) {
    b.extend_from_slice(&v.to_le_bytes());
}

pub(super) fn put_str(b: &mut Vec<u8>, s: &str) {
    put_u32(b, s.len() as u32);
    b.extend_from_slice(s.as_bytes());
}

pub(super) fn put_opt<T>(b: &mut Vec<u8>, v: Option<T>, put: impl FnOnce(&mut Vec<u8>, T)) {
    match v {
        Some(x) => {
            b.push(1);
            put(b, x);
        }
        None => b.push(0),
    }
}

/// The request for a run of `mesher` on `input` with `params` (module docs); `forward`: the
/// child is to forward the mesher's progress.
pub(super) fn encode_request(
    mesher: &str,
    input: &Pslg,
    params: &Params,
    forward: bool,
) -> Vec<u8> {
    let mut b = Vec::with_capacity(
        64 + mesher.len()
            + 16 * (input.points.len() + input.holes.len())
            + 8 * input.segments.len(),
    );
    b.extend_from_slice(REQUEST_MAGIC);
    put_u32(&mut b, VERSION);
    put_str(&mut b, mesher);
    put_opt(&mut b, params.min_angle, put_f64);
    put_opt(&mut b, params.max_area, put_f64);
    put_opt(&mut b, params.max_edge, put_f64);
    put_opt(&mut b, params.budget.max_steps, put_u64);
    put_opt(&mut b, params.budget.max_vertices, |b, v| {
        put_u64(b, v as u64)
    });
    put_opt(&mut b, params.budget.max_time, |b, d| {
        put_u64(b, d.as_secs());
        put_u32(b, d.subsec_nanos());
    });
    put_opt(&mut b, params.max_rounding, put_f64);
    put_opt(&mut b, params.switches.as_deref(), put_str);
    put_opt(&mut b, params.threads, |b, n| put_u64(b, n.get() as u64));
    b.push(u8::from(forward));
    put_u64(&mut b, input.points.len() as u64);
    for p in &input.points {
        put_f64(&mut b, p[0]);
        put_f64(&mut b, p[1]);
    }
    put_u64(&mut b, input.segments.len() as u64);
    for s in &input.segments {
        put_u32(&mut b, s[0]);
        put_u32(&mut b, s[1]);
    }
    put_u64(&mut b, input.holes.len() as u64);
    for h in &input.holes {
        put_f64(&mut b, h[0]);
        put_f64(&mut b, h[1]);
    }
    put_opt(&mut b, input.hexagon, |b, h| {
        put_f64(b, h.center[0]);
        put_f64(b, h.center[1]);
        put_f64(b, h.circumradius);
        put_f64(b, h.turn.cos);
        put_f64(b, h.turn.sin);
    });
    put_u64(&mut b, input.labels.regions.len() as u64);
    for r in &input.labels.regions {
        put_f64(&mut b, r.point[0]);
        put_f64(&mut b, r.point[1]);
        put_f64(&mut b, r.attribute);
        put_opt(&mut b, r.max_area, put_f64);
    }
    b
}

/// A stop reason: a tag byte, then its figure or words.
pub(super) fn put_stop(b: &mut Vec<u8>, stop: &StopReason) {
    let duration = |b: &mut Vec<u8>, tag: u8, d: &Duration| {
        b.push(tag);
        put_u64(b, d.as_secs());
        put_u32(b, d.subsec_nanos());
    };
    match stop {
        StopReason::Steps(max) => {
            b.push(0);
            put_u64(b, *max);
        }
        StopReason::Vertices(max) => {
            b.push(1);
            put_u64(b, *max as u64);
        }
        StopReason::Time(max) => duration(b, 2, max),
        StopReason::Rounds(max) => {
            b.push(3);
            put_u32(b, *max);
        }
        StopReason::Stalled(why) => {
            b.push(4);
            put_str(b, why);
        }
        StopReason::Timeout(after) => duration(b, 5, after),
        StopReason::Reported(words) => {
            b.push(6);
            put_str(b, words);
        }
        StopReason::VertexLimit { needed, limit } => {
            b.push(7);
            put_u64(b, *needed as u64);
            put_u64(b, *limit as u64);
        }
        // `StopReason` is non-exhaustive: a reason this protocol does not know yet travels
        // as its words.
        other => {
            b.push(6);
            put_str(b, &other.to_string());
        }
    }
}

pub(super) fn encode_run(b: &mut Vec<u8>, run: &MeshRun, peak_rss_bytes: u64) {
    b.push(0);
    b.push(u8::from(run.complete));
    put_opt(b, run.stop_reason.as_ref(), put_stop);
    put_u64(b, run.steps);
    put_u64(b, run.elapsed.as_secs());
    put_u32(b, run.elapsed.subsec_nanos());
    put_u64(b, peak_rss_bytes);
    put_u64(b, run.mesh.vertices.len() as u64);
    for v in &run.mesh.vertices {
        put_f64(b, v[0]);
        put_f64(b, v[1]);
    }
    put_u64(b, run.mesh.triangles.len() as u64);
    for t in &run.mesh.triangles {
        for &i in t {
            put_u32(b, i);
        }
    }
}

/// Bounds-checked reading of the binary format: a short or malformed message is an error,
/// never a panic or a huge allocation.
pub(super) struct Reader<'a> {
    buf: &'a [u8],
    pos: usize,
    what: &'static str,
}

impl<'a> Reader<'a> {
    fn bad(&self, detail: &str) -> Error {
        Error::mesher(
            "isolate",
            format!("malformed {} at byte {}: {detail}", self.what, self.pos),
        )
    }

    fn take(&mut self, n: usize) -> Result<&'a [u8]> {
        match self.pos.checked_add(n) {
            Some(end) if end <= self.buf.len() => {
                let s = &self.buf[self.pos..end];
                self.pos = end;
                Ok(s)
            }
            _ => Err(self.bad(&format!("{n} more bytes expected"))),
        }
    }

    fn u8(&mut self) -> Result<u8> {
        Ok(self.take(1)?[0])
    }

    fn u32(&mut self) -> Result<u32> {
        let s = self.take(4)?;
        Ok(u32::from_le_bytes([s[0], s[1], s[2], s[3]]))
    }

    fn u64(&mut self) -> Result<u64> {
        let mut a = [0u8; 8];
        a.copy_from_slice(self.take(8)?);
        Ok(u64::from_le_bytes(a))
    }

    fn f64(&mut self) -> Result<f64> {
        Ok(f64::from_bits(self.u64()?))
    }

    fn flag(&mut self) -> Result<bool> {
        match self.u8()? {
            0 => Ok(false),
            1 => Ok(true),
            b => Err(self.bad(&format!("flag byte {b}"))),
        }
    }

    fn str(&mut self) -> Result<String> {
        let n = self.u32()? as usize;
        let bytes = self.take(n)?;
        String::from_utf8(bytes.to_vec()).map_err(|_| self.bad("string is not UTF-8"))
    }

    fn duration(&mut self) -> Result<Duration> {
        let secs = self.u64()?;
        let nanos = self.u32()?;
        if nanos >= 1_000_000_000 {
            return Err(self.bad("nanoseconds out of range"));
        }
        Ok(Duration::new(secs, nanos))
    }

    /// A stop reason as `put_stop` wrote it.
    fn stop(&mut self) -> Result<StopReason> {
        Ok(match self.u8()? {
            0 => StopReason::Steps(self.u64()?),
            1 => StopReason::Vertices(usize::try_from(self.u64()?).unwrap_or(usize::MAX)),
            2 => StopReason::Time(self.duration()?),
            3 => StopReason::Rounds(self.u32()?),
            4 => StopReason::Stalled(self.str()?),
            5 => StopReason::Timeout(self.duration()?),
            6 => StopReason::Reported(self.str()?),
            7 => StopReason::VertexLimit {
                needed: usize::try_from(self.u64()?).unwrap_or(usize::MAX),
                limit: usize::try_from(self.u64()?).unwrap_or(usize::MAX),
            },
            b => return Err(self.bad(&format!("stop reason tag {b}"))),
        })
    }

    /// A count of items of `item_bytes` each that must fit in what is left.
    fn count(&mut self, item_bytes: usize) -> Result<usize> {
        let n = self.u64()?;
        let left = (self.buf.len() - self.pos) as u64;
        if n.checked_mul(item_bytes as u64)
            .is_none_or(|total| total > left)
        {
            return Err(self.bad(&format!("count {n} exceeds the message")));
        }
        Ok(n as usize)
    }

    fn points(&mut self) -> Result<Vec<[f64; 2]>> {
        let n = self.count(16)?;
        (0..n).map(|_| Ok([self.f64()?, self.f64()?])).collect()
    }

    fn finish(&self) -> Result<()> {
        if self.pos == self.buf.len() {
            Ok(())
        } else {
            Err(self.bad("trailing bytes"))
        }
    }
}

/// The mesher's name, the input, the parameters and whether to forward progress, as
/// `encode_request` wrote them.
pub(super) fn decode_request(buf: &[u8]) -> Result<(String, Pslg, Params, bool)> {
    let mut r = Reader {
        buf,
        pos: 0,
        what: "request",
    };
    if r.take(4)? != REQUEST_MAGIC {
        return Err(r.bad("not a hexmesh request"));
    }
    let version = r.u32()?;
    if version != VERSION {
        return Err(r.bad(&format!("version {version}, expected {VERSION}")));
    }
    let name = r.str()?;
    let min_angle = if r.flag()? { Some(r.f64()?) } else { None };
    let max_area = if r.flag()? { Some(r.f64()?) } else { None };
    let max_edge = if r.flag()? { Some(r.f64()?) } else { None };
    let max_steps = if r.flag()? { Some(r.u64()?) } else { None };
    let max_vertices = if r.flag()? {
        Some(usize::try_from(r.u64()?).unwrap_or(usize::MAX))
    } else {
        None
    };
    let max_time = if r.flag()? {
        let secs = r.u64()?;
        let nanos = r.u32()?;
        if nanos >= 1_000_000_000 {
            return Err(r.bad("nanoseconds out of range"));
        }
        Some(Duration::new(secs, nanos))
    } else {
        None
    };
    let max_rounding = if r.flag()? { Some(r.f64()?) } else { None };
    let switches = if r.flag()? { Some(r.str()?) } else { None };
    let threads = if r.flag()? {
        let n = usize::try_from(r.u64()?).unwrap_or(usize::MAX);
        Some(std::num::NonZeroUsize::new(n).ok_or_else(|| r.bad("zero threads"))?)
    } else {
        None
    };
    let forward = r.flag()?;
    let points = r.points()?;
    let m = r.count(8)?;
    let segments = (0..m)
        .map(|_| Ok([r.u32()?, r.u32()?]))
        .collect::<Result<Vec<_>>>()?;
    let holes = r.points()?;
    let hexagon = if r.flag()? {
        Some(Hexagon {
            center: [r.f64()?, r.f64()?],
            circumradius: r.f64()?,
            turn: Turn {
                cos: r.f64()?,
                sin: r.f64()?,
            },
        })
    } else {
        None
    };
    // x, y, attribute and the absence flag at least.
    let nr = r.count(25)?;
    let regions = (0..nr)
        .map(|_| {
            Ok(Region {
                point: [r.f64()?, r.f64()?],
                attribute: r.f64()?,
                max_area: if r.flag()? { Some(r.f64()?) } else { None },
            })
        })
        .collect::<Result<Vec<_>>>()?;
    r.finish()?;
    let params = Params {
        min_angle,
        max_area,
        max_edge,
        max_rounding,
        budget: Budget {
            max_steps,
            max_vertices,
            max_time,
        },
        switches,
        threads,
        progress: None,
    };
    // The other labels stay in the parent, which writes the mesh; the regions travel, since
    // `triangle` meshes with their area limits.
    let input = Pslg {
        points,
        segments,
        holes,
        hexagon,
        labels: Labels {
            regions,
            ..Labels::default()
        },
    };
    Ok((name, input, params, forward))
}

/// A refusal of a PSLG whose segments do not enclose a domain (`Pslg::check_enclosed`), or
/// that is not a polygonal domain (`rhomb`, paper 001 Sec. 3), as a kind byte and up to three
/// indices, so that the parent can name the file's lines.
pub(super) fn domain_refusal(problem: &InputError) -> Option<(u8, [usize; 3])> {
    match *problem {
        InputError::DanglingSegment { segment, vertex } => Some((0, [segment, vertex, 0])),
        InputError::BranchingSegment {
            segment,
            vertex,
            count,
        } => Some((1, [segment, vertex, count])),
        InputError::SegmentInsideDomain { segment } => Some((2, [segment, 0, 0])),
        InputError::SegmentOutsideDomain { segment } => Some((3, [segment, 0, 0])),
        InputError::PointOutsideDomain { point } => Some((4, [point, 0, 0])),
        InputError::NoEnclosedRegion { segments, cause } => {
            let cause = match cause {
                Unenclosed::Open => 0,
                Unenclosed::Holes => 1,
                Unenclosed::Collinear => 2,
            };
            Some((5, [segments, cause, 0]))
        }
        _ => None,
    }
}

/// The inverse of `domain_refusal`.
pub(super) fn domain_problem(kind: u8, [a, b, c]: [usize; 3]) -> Option<InputError> {
    Some(match kind {
        0 => InputError::DanglingSegment {
            segment: a,
            vertex: b,
        },
        1 => InputError::BranchingSegment {
            segment: a,
            vertex: b,
            count: c,
        },
        2 => InputError::SegmentInsideDomain { segment: a },
        3 => InputError::SegmentOutsideDomain { segment: a },
        4 => InputError::PointOutsideDomain { point: a },
        5 => InputError::NoEnclosedRegion {
            segments: a,
            cause: match b {
                0 => Unenclosed::Open,
                1 => Unenclosed::Holes,
                2 => Unenclosed::Collinear,
                _ => return None,
            },
        },
        _ => return None,
    })
}

pub(super) fn decode_answer(buf: &[u8], mesher: &str) -> Result<Isolated> {
    let mut r = Reader {
        buf,
        pos: 0,
        what: "answer",
    };
    match r.u8()? {
        0 => {}
        1 => {
            let name = r.str()?;
            let message = r.str()?;
            return Err(Error::Mesher {
                mesher: if name.is_empty() {
                    mesher.to_string()
                } else {
                    name
                },
                message,
            });
        }
        2 => {
            let first = usize::try_from(r.u64()?).unwrap_or(usize::MAX);
            let second = usize::try_from(r.u64()?).unwrap_or(usize::MAX);
            let (distance, needed, allowed) = (r.f64()?, r.f64()?, r.f64()?);
            r.finish()?;
            return Err(Error::input(InputError::Rounding {
                first,
                second,
                distance,
                needed,
                allowed,
            }));
        }
        3 => {
            let index = usize::try_from(r.u64()?).unwrap_or(usize::MAX);
            let distance = r.f64()?;
            r.finish()?;
            return Err(Error::input(InputError::NearBoundary { index, distance }));
        }
        4 => {
            let kind = r.u8()?;
            let mut v = [0usize; 3];
            for slot in &mut v {
                *slot = usize::try_from(r.u64()?).unwrap_or(usize::MAX);
            }
            r.finish()?;
            return match domain_problem(kind, v) {
                Some(problem) => Err(Error::input(problem)),
                None => Err(r.bad(&format!("domain refusal kind {kind}"))),
            };
        }
        b => return Err(r.bad(&format!("status byte {b}"))),
    }
    let complete = r.flag()?;
    let stop_reason = if r.flag()? { Some(r.stop()?) } else { None };
    let steps = r.u64()?;
    let secs = r.u64()?;
    let nanos = r.u32()?;
    if nanos >= 1_000_000_000 {
        return Err(r.bad("nanoseconds out of range"));
    }
    let peak_rss_bytes = r.u64()?;
    let vertices = r.points()?;
    let nt = r.count(12)?;
    let triangles = (0..nt)
        .map(|_| Ok([r.u32()?, r.u32()?, r.u32()?]))
        .collect::<Result<Vec<_>>>()?;
    r.finish()?;
    Ok(Isolated {
        run: MeshRun {
            mesh: TriMesh {
                vertices,
                triangles,
            },
            complete,
            stop_reason,
            steps,
            elapsed: Duration::new(secs, nanos),
        },
        peak_rss_bytes,
    })
}
