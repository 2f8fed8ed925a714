// C's printf("%.17g") for a binary64 (conformance/README.md, expected.txt): 17 significant digits correctly rounded,
// an exponent (two digits at least) when the decimal exponent is below -4 or at least 17, trailing zeros removed.
export function formatG17(x) {
  if (!Number.isFinite(x)) throw new RangeError(`formatG17: ${x} is not finite`);
  const sign = x < 0 || Object.is(x, -0) ? '-' : '';
  const [mant, expText] = Math.abs(x).toExponential(16).split('e');
  const exp = Number(expText);
  const digits = mant.replace('.', '');
  const trim = (s) => (s.includes('.') ? s.replace(/0+$/, '').replace(/\.$/, '') : s);
  if (exp < -4 || exp >= 17) {
    const e = Math.abs(exp).toString().padStart(2, '0');
    return `${sign}${trim(mant)}e${exp < 0 ? '-' : '+'}${e}`;
  }
  if (exp >= 0) return sign + trim(`${digits.slice(0, exp + 1)}.${digits.slice(exp + 1)}`);
  return sign + trim(`0.${'0'.repeat(-exp - 1)}${digits}`);
}
