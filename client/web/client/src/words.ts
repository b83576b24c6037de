// 64-bit words as two 32-bit halves: IEEE-754 bit patterns and FNV-1a without
// BigInt arithmetic in the hot loop (a view hash mixes six words per body held).

const scratch = new DataView(new ArrayBuffer(8));

/** The IEEE-754 bit pattern of `value`: [high 32 bits, low 32 bits]. */
export function doubleWords(value: number): [number, number] {
  scratch.setFloat64(0, value, true);
  return [scratch.getUint32(4, true), scratch.getUint32(0, true)];
}

/** The double whose IEEE-754 bit pattern is `bits`. */
export function doubleFromBits(bits: bigint): number {
  scratch.setBigUint64(0, BigInt.asUintN(64, bits), true);
  return scratch.getFloat64(0, true);
}

/** The IEEE-754 bit pattern of `value` as an unsigned 64-bit integer. */
export function doubleBits(value: number): bigint {
  scratch.setFloat64(0, value, true);
  return scratch.getBigUint64(0, true);
}

/** An unsigned 64-bit integer's halves: [high 32 bits, low 32 bits]. */
export function bigintWords(value: bigint): [number, number] {
  return [Number((value >> 32n) & 0xffffffffn), Number(value & 0xffffffffn)];
}

// A double's two halves through one buffer, without a DataView call per word; on a
// big-endian machine (none that runs a browser today) the halves swap.
const f64 = new Float64Array(1);
const u32 = new Uint32Array(f64.buffer);
const LITTLE_ENDIAN = new Uint8Array(new Uint32Array([1]).buffer)[0] === 1;
const LO = LITTLE_ENDIAN ? 0 : 1;
const HI = LITTLE_ENDIAN ? 1 : 0;

/**
 * FNV-1a over 64-bit words (docs/PROTOCOL.md 5.6): h = (h XOR word) * 0x100000001b3
 * modulo 2^64, from h = 0xcbf29ce484222325. The prime is 2^40 + 0x1b3, so the
 * product is (h << 40) + h * 0x1b3, computed on 32-bit halves: every partial sum
 * stays below 2^42, exact in a double.
 */
export class Fnv64 {
  private hi = 0xcbf29ce4;
  private lo = 0x84222325;

  mix(hi: number, lo: number): void {
    const xlo = (this.lo ^ lo) >>> 0;
    const xhi = (this.hi ^ hi) >>> 0;
    const low = xlo * 0x1b3;
    const newLo = low >>> 0;
    const carry = (low - newLo) / 4294967296;
    // (h << 40) moves the low 24 bits of h's low half into the high half.
    this.hi = (Math.imul(xhi, 0x1b3) + carry + ((xlo & 0xffffff) << 8)) >>> 0;
    this.lo = newLo;
  }

  mixDouble(value: number): void {
    f64[0] = value;
    this.mix(u32[HI], u32[LO]);
  }

  value(): bigint {
    return (BigInt(this.hi) << 32n) | BigInt(this.lo);
  }
}
