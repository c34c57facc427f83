// What body() throws, to assert on its class, code and message together (fails the test when it throws
// nothing).
export function thrown(body) {
  try {
    body();
  } catch (error) {
    return error;
  }
  throw new Error('expected an error');
}
