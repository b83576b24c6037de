// The waits of a session: every call that waits registers what it waits for, and
// every event that may bring it (a message, a change of state) calls notify().

interface Waiter {
  ready: () => boolean;
  wake: () => void;
}

export class Waiters {
  private readonly waiters = new Set<Waiter>();

  /** Resolves to settle(false) at the first notify() at which `ready()` holds, or to
   * settle(true) after `timeoutMs`, whichever comes first. */
  wait<T>(ready: () => boolean, timeoutMs: number, settle: (timedOut: boolean) => T): Promise<T> {
    return new Promise((resolve) => {
      const timer = setTimeout(() => {
        this.waiters.delete(waiter);
        resolve(settle(true));
      }, timeoutMs);
      const waiter: Waiter = {
        ready,
        wake: () => {
          clearTimeout(timer);
          resolve(settle(false));
        },
      };
      this.waiters.add(waiter);
    });
  }

  /** Wakes every wait whose condition holds now. */
  notify(): void {
    for (const waiter of [...this.waiters]) {
      if (waiter.ready()) {
        this.waiters.delete(waiter);
        waiter.wake();
      }
    }
  }
}
